import { encodePFM, encodePNG, opaque } from '../image-io.js';
import { openVptPage, renderScene, type RenderResult, type VptPageSession } from '../render.js';
import { readSceneFile } from '../scene-files.js';
import { parseRenderArgs, RENDER_USAGE, stepFileName } from './args.js';
import { oneLine, processIO, type CliIO } from './io.js';
import { checkOutputFile, writeOutputFile } from './output-file.js';

/** Progress lines on stderr: none in the first PROGRESS_AFTER_MS, then at most one per PROGRESS_EVERY_MS. */
const PROGRESS_AFTER_MS = 3000;
const PROGRESS_EVERY_MS = 5000;

export function progressPrinter(io: CliIO): (done: number, total: number, ms: number) => void {
  let last = -Infinity;
  return (done, total, ms) => {
    if (ms < PROGRESS_AFTER_MS || ms - last < PROGRESS_EVERY_MS || done >= total) return;
    last = ms;
    const left = (ms / done) * (total - done);
    io.err(
      `vpt-render: ${done}/${total} iterations (${((100 * done) / total).toFixed(1)} %), ${(ms / 1000).toFixed(0)} s, about ${duration(left)} left`,
    );
  };
}

function duration(ms: number): string {
  const s = Math.round(ms / 1000);
  if (s < 120) return `${s} s`;
  if (s < 7200) return `${Math.round(s / 60)} min`;
  return `${(s / 3600).toFixed(1)} h`;
}

const EMPTY_CHAIN =
  "the scene's post chain is empty, so there is no LDR image to write with -o (use --pfm for the HDR image)";

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
    // One step (the scene's own, or --time A) or the steps A..B of --time A:B, each to its own files.
    const steps = args.time
      ? Array.from({ length: args.time.last - args.time.first + 1 }, (_, i) => args.time!.first + i)
      : [undefined];
    const numbered = steps.length > 1;
    const outputs = steps.map((t) => ({
      time: t,
      png: args.output !== undefined && t !== undefined ? stepFileName(args.output, t, numbered) : args.output,
      pfm: args.pfm !== undefined && t !== undefined ? stepFileName(args.pfm, t, numbered) : args.pfm,
    }));
    // Output paths first: a folder or an unwritable file must not fail after the whole render.
    for (const o of outputs) {
      if (o.png !== undefined) checkOutputFile(o.png, '-o');
      if (o.pfm !== undefined) checkOutputFile(o.pfm, '--pfm');
    }
    const { description, baseDir } = readSceneFile(args.scene);
    if (args.output !== undefined && Array.isArray(description.post) && description.post.length === 0)
      throw new Error(EMPTY_CHAIN);
    // Several steps share one browser and page.
    const session: VptPageSession | undefined = numbered
      ? await openVptPage({ root: null, onConsole: args.verbose ? (line) => io.err(line) : undefined })
      : undefined;
    let result!: RenderResult;
    const perStep: Record<string, unknown>[] = [];
    try {
      for (const o of outputs) {
        result = await renderScene(o.time === undefined ? description : { ...description, time: o.time }, {
          baseDir,
          backend: args.backend,
          iterations: args.iterations,
          width: args.width,
          height: args.height,
          seed: args.seed,
          sceneRoot: args.root,
          ...(args.timeLimit !== undefined ? { timeLimitMs: args.timeLimit * 1000 } : {}),
          ...(args.temporal ? { temporal: true } : {}),
          ...(session ? { session } : {}),
          onProgress: progressPrinter(io),
          onConsole: args.verbose ? (line) => io.err(line) : undefined,
        });
        if (o.png !== undefined) {
          if (!result.ldr) throw new Error(EMPTY_CHAIN);
          const png = encodePNG(args.keepAlpha ? result.ldr : opaque(result.ldr), result.width, result.height);
          writeOutputFile(o.png, png, '-o');
        }
        if (o.pfm !== undefined) writeOutputFile(o.pfm, encodePFM(result.hdr, result.width, result.height), '--pfm');
        if (numbered)
          perStep.push({
            time: o.time,
            ...(o.png !== undefined ? { output: o.png } : {}),
            ...(o.pfm !== undefined ? { pfm: o.pfm } : {}),
            ...result.timings,
          });
      }
    } finally {
      await session?.close();
    }
    io.out(
      JSON.stringify({
        ...(numbered ? { steps: perStep } : result.timings),
        ...(outputs[0].time !== undefined && !numbered ? { time: outputs[0].time } : {}),
        width: result.width,
        height: result.height,
        backend: result.backend.kind,
        device: result.backend.renderer,
        gpuBytes: result.gpuBytes,
        volumeDims: result.volumeDims,
        ...(result.bricking ? { bricking: result.bricking } : {}),
        // What the renderer chose (MCRT auto: the estimator and why).
        ...(Object.keys(result.rendererStats ?? {}).length ? { rendererStats: result.rendererStats } : {}),
        // What the PFM holds: the estimate after these post steps (['denoise'] when it was denoised).
        ...(args.pfm !== undefined ? { hdrPostSteps: result.hdrPostSteps } : {}),
        ...(args.temporal ? { temporal: true } : {}),
        ...(result.warnings.length > 0 ? { warnings: result.warnings } : {}),
      }),
    );
    for (const w of result.warnings) io.err(`vpt-render: warning: ${w}`);
    if (result.timings.timeLimited)
      io.err(
        `vpt-render: the time limit of ${args.timeLimit} s stopped the render after ${result.timings.iterations} iterations`,
      );
    return 0;
  } catch (e) {
    io.err(`vpt-render: ${oneLine(e)}`);
    if (verbose && e instanceof Error && e.stack) io.err(e.stack);
    return 1;
  }
}
