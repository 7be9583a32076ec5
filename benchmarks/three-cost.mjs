#!/usr/bin/env node
/**
 * The frame cost of @vpt/three over plain vpt (docs/benchmarks.md, "three.js"): per frame,
 * A = plain vpt (one EAM iteration of the 64³ blob and its HDR image, on its own context) and
 * B = the same volume as a VptVolume in a three.js scene with a lit cylinder through it
 * (three's opaque pass, the volume with its rays ending at the mesh depth, the composite and
 * the depth pass, the output pass), each frame synchronised by a 1-pixel read (WebGL 2) or
 * onSubmittedWorkDone (WebGPU). Timed batches alternate A B A B; the figure is the median of
 * the ratios B / A of neighbouring batches, printed with the load average. WebGLRenderer on
 * vpt's WebGL 2 backend (shared context) and WebGPURenderer on vpt's WebGPU backend (shared
 * device): --three webgl|webgpu|both.
 *
 *   pnpm run build && node benchmarks/three-cost.mjs [--sizes 64,128] [--rounds N] [--batch N] [--three webgl|webgpu|both]
 */
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const { sizes, rounds, batch, three } = parseCliOrExit({
  name: 'node benchmarks/three-cost.mjs',
  synopsis: '[--sizes 64,128] [--rounds N] [--batch N] [--three webgl|webgpu|both]',
  summary: 'ms per frame of plain vpt and of @vpt/three, interleaved, as ratios (needs pnpm run build).',
  options: {
    sizes: { type: 'string', default: '64,128', description: 'image sides in pixels, comma-separated' },
    rounds: { type: 'integer', min: 1, default: 6, description: 'interleaved rounds (one batch of each per round)' },
    batch: { type: 'integer', min: 1, default: 10, description: 'frames per timed batch' },
    three: { type: 'string', choices: ['webgl', 'webgpu', 'both'], default: 'both', description: 'three.js renderer' },
  },
});
const sides = sizes.split(',').map((s) => Number(s.trim()));
if (!sides.every((s) => Number.isInteger(s) && s > 0 && s <= 1024)) {
  console.error(`--sizes must be integers in [1, 1024], comma-separated; got '${sizes}'`);
  process.exit(2);
}
// After the arguments, so that --help works before a build.
const { launchChromium, startStaticServer } = await import('../packages/headless/dist/index.js');

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');
const median = (a) => [...a].sort((x, y) => x - y)[a.length >> 1];

/** Runs in the page: the A and B frames of one size, interleaved; returns ms per frame per batch. */
async function measure(o) {
  const { THREE, core, eam, vt3 } = window.ref;
  const webgpu = o.three === 'webgpu';
  const vscene = {
    volume: core.createProceduralVolume('blob', 64),
    transferFunction: core.rampTransferFunction([1, 0.8, 0.6]),
    lights: [],
    environment: { type: 'constant', radiance: [0.1, 0.1, 0.1] },
    densityScale: 20,
    seed: 1,
  };
  const cam = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
  const px = new Uint8Array(4);
  const canvasA = document.createElement('canvas');
  const A = await core.RenderContext.create({
    backend: webgpu ? 'webgpu' : 'webgl2',
    canvas: canvasA,
    width: o.size,
    height: o.size,
    renderer: new eam.EamRenderer(),
  });
  A.setScene({ ...vscene, camera: cam });
  const canvasB = document.createElement('canvas');
  document.body.append(canvasB);
  let renderer;
  let compositor;
  if (webgpu) {
    const adapter = await navigator.gpu.requestAdapter();
    renderer = new THREE.WebGPURenderer({ canvas: canvasB, requiredLimits: vt3.vptRequiredLimits(adapter) });
    await renderer.init();
  } else {
    renderer = new THREE.WebGLRenderer({ canvas: canvasB });
  }
  renderer.setPixelRatio(1);
  renderer.setSize(o.size, o.size, false);
  compositor = webgpu ? new vt3.VptWebGPUCompositor(renderer) : new vt3.VptCompositor(renderer);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 10);
  camera.position.set(0, 0, 2);
  camera.lookAt(0, 0, 0);
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(0.05, 0.05, 1.4), new THREE.MeshStandardMaterial());
  mesh.rotation.z = 1;
  scene.add(mesh, new THREE.DirectionalLight(0xffffff, 2));
  const vol = new vt3.VptVolume({ renderer: new eam.EamRenderer(), scene: vscene, maxSamples: 1e9 });
  scene.add(vol);
  await compositor.prepare(scene);
  const glA = webgpu ? null : canvasA.getContext('webgl2');
  const glB = webgpu ? null : renderer.getContext();
  const frames = {
    vpt: async () => {
      A.iterate(1);
      A.renderImage();
      if (webgpu) await A.backend.device.queue.onSubmittedWorkDone();
      else glA.readPixels(0, 0, 1, 1, glA.RGBA, glA.UNSIGNED_BYTE, px);
    },
    three: async () => {
      compositor.render(scene, camera);
      if (webgpu) await renderer.backend.device.queue.onSubmittedWorkDone();
      else glB.readPixels(0, 0, 1, 1, glB.RGBA, glB.UNSIGNED_BYTE, px);
    },
  };
  const time = async (f, n) => {
    const t0 = performance.now();
    for (let i = 0; i < n; i++) await f();
    return (performance.now() - t0) / n;
  };
  await time(frames.vpt, 3);
  await time(frames.three, 3);
  const out = { vpt: [], three: [] };
  for (let r = 0; r < o.rounds; r++) {
    // A B in even rounds, B A in odd ones: neither always runs first.
    const order = r % 2 ? ['three', 'vpt'] : ['vpt', 'three'];
    for (const k of order) out[k].push(await time(frames[k], o.batch));
  }
  A.dispose();
  vol.dispose();
  compositor.dispose();
  renderer.dispose();
  return out;
}

const server = await startStaticServer(ROOT);
const browser = await launchChromium();
try {
  const kinds = three === 'both' ? ['webgl', 'webgpu'] : [three];
  console.log(`three-cost: ${rounds} rounds of ${batch} frames, EAM, blob 64³; load ${load()}`);
  for (const kind of kinds) {
    const page = await browser.newPage();
    page.on('pageerror', (e) => console.error(`page error: ${e.message}`));
    await page.goto(
      new URL(kind === 'webgpu' ? 'tests/pages/three-webgpu.html' : 'tests/pages/three.html', server.url).href,
    );
    await page.waitForFunction(() => window.__ready === true, { timeout: 60_000 });
    for (const size of sides) {
      const r = await page.evaluate(measure, { size, rounds, batch, three: kind });
      const ratios = r.three.map((b, i) => b / r.vpt[i]);
      console.log(
        `${kind === 'webgpu' ? 'WebGPURenderer' : 'WebGLRenderer '} ${size}²: plain vpt ${median(r.vpt).toFixed(2)} ms/frame, ` +
          `@vpt/three ${median(r.three).toFixed(2)} ms/frame, ratio × ${median(ratios).toFixed(2)} ` +
          `(min ${Math.min(...ratios).toFixed(2)}, max ${Math.max(...ratios).toFixed(2)}); load ${load()}`,
      );
    }
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
