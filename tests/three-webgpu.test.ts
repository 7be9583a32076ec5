/**
 * @vpt/three with three.js's WebGPURenderer (`@vpt/three/webgpu`): vpt's WebGPU backend on
 * three's own GPUDevice. Checked against the other backend (core's WebGL 2 render of the same
 * scene and camera) and CPU expectations, as tests/three.test.ts does for WebGLRenderer.
 */
import { writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { encodePNG } from '../packages/headless/src/index.js';
import { useThreePage } from './helpers/three-page.js';

const N = 32;
const three = useThreePage('tests/pages/three-webgpu.html');

function savePng(name: string, rgba: number[], w = N, h = N): void {
  const px = new Uint8Array(w * h * 4);
  for (let i = 0; i < w * h; i++) {
    for (let c = 0; c < 3; c++) px[4 * i + c] = Math.round(255 * Math.min(1, Math.max(0, rgba[4 * i + c])));
    px[4 * i + 3] = 255;
  }
  writeFileSync(`/tmp/vpt-three-webgpu-${name}.png`, encodePNG(px, w, h));
}

describe('@vpt/three on WebGPURenderer (vpt on three’s GPUDevice)', () => {
  it('composites EAM as core’s WebGL 2 render; a plane inside a cube is attenuated exactly; the depth is representative', async () => {
    const m = [0.1, 0.5, 0.9];
    const color = [1, 0.5, 0.25];
    const green = [0.1, 0.9, 0.2];
    const sigma = 2;
    const out = await three().run(
      async (h3, n, m, color, green, sigma) => {
        const { THREE, eam, vt3 } = (window as any).ref;
        const adapter = await navigator.gpu.requestAdapter();
        const setup = async (float: boolean) => {
          const canvas = document.createElement('canvas');
          document.body.append(canvas);
          const renderer = new THREE.WebGPURenderer({
            canvas,
            antialias: false,
            requiredLimits: vt3.vptRequiredLimits(adapter),
          });
          renderer.setPixelRatio(1);
          renderer.setSize(n, n, false);
          await renderer.init();
          const compositor = new vt3.VptWebGPUCompositor(renderer, float ? { type: THREE.FloatType } : {});
          const scene = new THREE.Scene();
          const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 10);
          camera.position.set(0, 0, 2);
          camera.lookAt(0, 0, 0);
          camera.updateMatrixWorld();
          renderer.setClearColor(h3.linear([0, 0, 0]), 1);
          return { renderer, compositor, scene, camera };
        };
        const read = async (s: any) => {
          const t = s.compositor.target;
          return Array.from(await s.renderer.readRenderTargetPixelsAsync(t, 0, 0, n, n)) as number[];
        };
        const first = await setup(false);
        const info = {
          webgpu: first.renderer.backend.isWebGPUBackend === true,
          float32Blendable: first.renderer.backend.device.features.has('float32-blendable'),
        };
        first.renderer.dispose();
        const float = info.float32Blendable;
        const res: Record<string, number[]> = {};
        // 1. No mesh: the blob, as core renders it on WebGL 2.
        {
          const s = await setup(float);
          const vscene = h3.vptScene('blob', 16, [1, 0.6, 0.3], 1, 12, [0, 0, 0]);
          const vol = new vt3.VptVolume({ renderer: new eam.EamRenderer(), scene: vscene, iterationsPerFrame: 8 });
          s.scene.add(vol);
          await s.compositor.prepare(s.scene);
          s.compositor.render(s.scene, s.camera);
          s.compositor.render(s.scene, s.camera);
          res.blob = await read(s);
          const camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
          res.core = Array.from(await h3.coreRender('eam', { ...vscene, camera }, n, 16));
          // vpt's context is disposed, three's device lives on: three still draws and reads back.
          vol.dispose();
          s.scene.remove(vol);
          s.renderer.setClearColor(h3.linear([1, 0, 0]), 1);
          s.compositor.render(s.scene, s.camera);
          res.afterDispose = (await read(s)).slice(0, 4);
          s.renderer.dispose();
        }
        // 2. A plane through a homogeneous cube's centre.
        {
          const s = await setup(float);
          const vol = new vt3.VptVolume({
            renderer: new eam.EamRenderer(),
            scene: h3.vptScene('cube', 8, color, 1, sigma, [0.5, 0.5, 0.5]),
            iterationsPerFrame: 16,
          });
          s.scene.add(vol);
          s.scene.add(
            new THREE.Mesh(new THREE.PlaneGeometry(3, 3), new THREE.MeshBasicMaterial({ color: h3.linear(m) })),
          );
          await s.compositor.prepare(s.scene);
          s.compositor.render(s.scene, s.camera);
          res.inside = await read(s);
          vol.dispose();
          s.renderer.dispose();
        }
        // 3. The dense sphere with a transparent plane in front of its medium (behind the box entry), and behind it.
        for (const [name, z] of [
          ['sphere', null],
          ['front', 0.42],
          ['behind', 0.2],
        ] as const) {
          const s = await setup(float);
          const vol = new vt3.VptVolume({
            renderer: new eam.EamRenderer(),
            scene: {
              ...h3.vptScene('sphere', 32, [1, 0.6, 0.3], 1, 40, [0, 0, 0]),
              transferFunction: {
                dimensions: '1d',
                points: [
                  { value: 0, color: [1, 0.6, 0.3], opacity: 0 },
                  { value: 1, color: [1, 0.6, 0.3], opacity: 1 },
                ],
              },
            },
            iterationsPerFrame: 8,
          });
          s.scene.add(vol);
          if (z !== null) {
            const plane = new THREE.Mesh(
              new THREE.PlaneGeometry(3, 3),
              new THREE.MeshBasicMaterial({ color: h3.linear(green), transparent: true, opacity: 0.5 }),
            );
            plane.position.z = z;
            s.scene.add(plane);
          }
          await s.compositor.prepare(s.scene);
          s.compositor.render(s.scene, s.camera);
          s.compositor.render(s.scene, s.camera);
          res[name] = await read(s);
          vol.dispose();
          s.renderer.dispose();
        }
        return { info, res };
      },
      N,
      m,
      color,
      green,
      sigma,
    );
    const { info, res } = out;
    for (const k of Object.keys(res)) if (res[k].length === N * N * 4) savePng(k, res[k]);
    // Disposing of the volume left three's GPUDevice alive (a shared device is never destroyed).
    expect(res.afterDispose).toEqual([1, 0, 0, 1]);
    expect(info.webgpu).toBe(true);
    // Half-float targets (without 'float32-blendable') round to 2^-11 relative.
    const tol = info.float32Blendable ? 2e-3 : 3e-3;
    // 1. Against core's WebGL 2 render: the other backend and the other three renderer.
    const c = (N / 2) * N * 4 + (N / 2) * 4;
    expect(res.core[c]).toBeGreaterThan(0.1);
    let sum = 0;
    for (let i = 0; i < res.core.length; i++) if (i % 4 !== 3) sum += Math.abs(res.blob[i] - res.core[i]);
    expect(sum / ((res.core.length * 3) / 4)).toBeLessThan(tol / 2);
    // 2. The CPU expectation c(1 − T) + T·m along each pixel-centre ray (as in three.test.ts).
    const t = Math.tan((20 * Math.PI) / 180);
    let n = 0;
    for (let y = 0; y < N; y++) {
      for (let x = 0; x < N; x++) {
        const sx = ((2 * (x + 0.5)) / N - 1) * t;
        const sy = (1 - (2 * (y + 0.5)) / N) * t;
        if (Math.abs(sx * 2) > 0.48 || Math.abs(sy * 2) > 0.48) continue;
        const T = Math.exp(-sigma * 0.5 * Math.hypot(sx, sy, 1));
        const i = 4 * (y * N + x);
        n++;
        for (let k = 0; k < 3; k++)
          expect(Math.abs(res.inside[i + k] - (color[k] * (1 - T) + T * m[k]))).toBeLessThan(tol);
      }
    }
    expect(n).toBeGreaterThan(300);
    // 3. Near the centre: the plane in front of the medium is blended over the volume, the one behind is hidden.
    let centre = 0;
    for (let y = N / 2 - 3; y < N / 2 + 3; y++) {
      for (let x = N / 2 - 3; x < N / 2 + 3; x++) {
        const i = 4 * (y * N + x);
        centre++;
        for (let k = 0; k < 3; k++) {
          expect(Math.abs(res.front[i + k] - (0.5 * green[k] + 0.5 * res.sphere[i + k]))).toBeLessThan(tol);
          expect(Math.abs(res.behind[i + k] - res.sphere[i + k])).toBeLessThan(1e-6);
        }
      }
    }
    expect(centre).toBe(36);
    expect(three().errors).toEqual([]);
  });
});
