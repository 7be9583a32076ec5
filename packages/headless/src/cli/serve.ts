#!/usr/bin/env node
import { runServe } from './serve-main.js';

const { code, server } = await runServe(process.argv.slice(2));
if (code !== null) process.exit(code);
for (const signal of ['SIGINT', 'SIGTERM'] as const) {
  process.once(signal, () => {
    void server?.close().then(() => process.exit(0));
  });
}
