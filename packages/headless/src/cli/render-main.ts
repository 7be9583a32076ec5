import fs from 'node:fs';
import path from 'node:path';
import { encodePFM, encodePNG, opaque } from '../image-io.js';
import { renderScene } from '../render.js';
import { readSceneFile } from '../scene-files.js';
import { parseRenderArgs, RENDER_USAGE } from './args.js';
import { oneLine, processIO, type CliIO } from './io.js';

function writeFile(file: string, data: Uint8Array): void {
  fs.mkdirSync(path.dirname(path.resolve(file)), { recursive: true });
  fs.writeFileSync(file, data);
}

/**
 * vpt-render: scene.json → PNG (LDR) and/or PFM (HDR), timings as one JSON line on
 * stdout. Returns the exit code: 0, or 1 with a one-line message on stderr.
 */
export async function runRender(argv: string[], io: CliIO = processIO): Promise<number> {
  let verbose = false;
  try {
    const args = parseRenderArgs(argv);
    verbose = args.verbose;
    if (args.help) {
      io.out(RENDER_USAGE);
      return 0;
    }
    const { description, baseDir } = readSceneFile(args.scene);
    const result = await renderScene(description, {
      baseDir,
      backend: args.backend,
      iterations: args.iterations,
      width: args.width,
      height: args.height,
      seed: args.seed,
      sceneRoot: args.root,
      onConsole: args.verbose ? (line) => io.err(line) : undefined,
    });
    if (args.output !== undefined) {
      if (!result.ldr)
        throw new Error(
          "the scene's post chain is empty, so there is no LDR image to write with -o (use --pfm for the HDR image)",
        );
      writeFile(args.output, encodePNG(args.keepAlpha ? result.ldr : opaque(result.ldr), result.width, result.height));
    }
    if (args.pfm !== undefined) writeFile(args.pfm, encodePFM(result.hdr, result.width, result.height));
    io.out(
      JSON.stringify({
        ...result.timings,
        width: result.width,
        height: result.height,
        backend: result.backend.kind,
        device: result.backend.renderer,
        gpuBytes: result.gpuBytes,
        volumeDims: result.volumeDims,
        ...(result.bricking ? { bricking: result.bricking } : {}),
        // What the PFM holds: the estimate after these post steps (['denoise'] when it was denoised).
        ...(args.pfm !== undefined ? { hdrPostSteps: result.hdrPostSteps } : {}),
        ...(result.warnings.length > 0 ? { warnings: result.warnings } : {}),
      }),
    );
    for (const w of result.warnings) io.err(`vpt-render: warning: ${w}`);
    return 0;
  } catch (e) {
    io.err(`vpt-render: ${oneLine(e)}`);
    if (verbose && e instanceof Error && e.stack) io.err(e.stack);
    return 1;
  }
}
