#!/usr/bin/env node
import { runRender } from './render-main.js';

// Exit explicitly: a browser that failed to close must not keep the CLI alive.
process.exit(await runRender(process.argv.slice(2)));
