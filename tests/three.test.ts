/**
 * @vpt/three (issue 27): a VptVolume drawn by VptCompositor on three.js's own WebGL 2
 * context. Images are checked against core's own renders of the same scene and camera, a
 * CPU expectation on a homogeneous cube, and three.js-only renders.
 */
import { writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { encodePNG } from '../packages/headless/src/index.js';
import { useThreePage } from './helpers/three-page.js';

const N = 32;
const three = useThreePage();

/** Save an HDR image (top row first) as an 8-bit PNG under /tmp, for looking at. */
function savePng(name: string, rgba: number[], w = N, h = N): void {
  const px = new Uint8Array(w * h * 4);
  for (let i = 0; i < w * h; i++) {
    for (let c = 0; c < 3; c++) px[4 * i + c] = Math.round(255 * Math.min(1, Math.max(0, rgba[4 * i + c])));
    px[4 * i + 3] = 255;
  }
  writeFileSync(`/tmp/vpt-three-${name}.png`, encodePNG(px, w, h));
}

function maxRgbDiff(a: number[], b: number[]): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

function meanRgbDiff(a: number[], b: number[]): number {
  let s = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) s += Math.abs(a[i] - b[i]);
  return s / ((a.length * 3) / 4);
}

const BG = [0.2, 0.3, 0.4];

describe('@vpt/three: VptVolume in a three.js scene', () => {
  it('without meshes equals core’s own render of the same scene and camera (EAM and MCRT)', async () => {
    const out = await three().run(
      async (h3, n, bg) => {
        const res: Record<string, number[][]> = {};
        for (const r of ['eam', 'mcrt']) {
          const s = h3.setup(n);
          const { eam, mcrt } = (window as any).ref;
          const vscene = {
            ...h3.vptScene('blob', 16, [1, 0.6, 0.3], 1, 12, bg),
            lights: [{ type: 'directional', direction: [0.48, 0.64, 0.6], irradiance: [3, 3, 3] }],
          };
          const vol = new (window as any).ref.vt3.VptVolume({
            renderer: r === 'eam' ? new eam.EamRenderer() : new mcrt.McrtRenderer(),
            scene: vscene,
            iterationsPerFrame: 8,
          });
          s.scene.add(vol);
          s.renderer.setClearColor(h3.linear(bg), 1);
          await s.compositor.prepare(s.scene);
          h3.frames(s, 2);
          const got = Array.from(h3.readTarget(s));
          const camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
          const want = Array.from(await h3.coreRender(r, { ...vscene, camera }, n, 16));
          res[r] = [got, want];
          vol.dispose();
          s.renderer.dispose();
        }
        return res;
      },
      N,
      BG,
    );
    for (const r of ['eam', 'mcrt']) {
      const [got, want] = out[r];
      savePng(`${r}-three`, got);
      savePng(`${r}-core`, want);
      // The volume is there: the centre differs from the background.
      const c = (N / 2) * N * 4 + (N / 2) * 4;
      expect(Math.abs(want[c + 2] - BG[2])).toBeGreaterThan(0.1);
      expect(meanRgbDiff(got, want)).toBeLessThan(r === 'eam' ? 1e-4 : 2e-3);
      if (r === 'eam') expect(maxRgbDiff(got, want)).toBeLessThan(2e-3);
    }
  });

  it('takes its transform from the object: moved, turned and scaled views equal core’s render', async () => {
    const out = await three().run(async (h3, n) => {
      const { eam, vt3 } = (window as any).ref;
      const vscene = h3.vptScene('blob', 16, [1, 0.6, 0.3], 1, 12, [0, 0, 0]);
      const camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
      const want = Array.from(await h3.coreRender('eam', { ...vscene, camera }, n, 8));
      const res: number[][] = [];
      // (object position, rotation about y, uniform scale, camera position, camera target):
      // each puts the camera at (0, 0, 2) of the volume's own frame, looking at its centre.
      const cases: [number[], number, number, number[], number[]][] = [
        [[0.3, -0.2, 0.1], 0, 1, [0.3, -0.2, 2.1], [0.3, -0.2, 0.1]],
        [[0, 0, 0], Math.PI / 2, 1, [2, 0, 0], [0, 0, 0]],
        [[0, 0, 0], 0, 2, [0, 0, 4], [0, 0, 0]],
      ];
      for (const [p, ry, k, cp, ct] of cases) {
        const s = h3.setup(n);
        const vol = new vt3.VptVolume({ renderer: new eam.EamRenderer(), scene: vscene, iterationsPerFrame: 8 });
        vol.position.set(p[0], p[1], p[2]);
        vol.rotation.set(0, ry, 0);
        vol.scale.setScalar(k);
        s.scene.add(vol);
        s.camera.position.set(cp[0], cp[1], cp[2]);
        s.camera.lookAt(ct[0], ct[1], ct[2]);
        s.camera.updateMatrixWorld();
        s.renderer.setClearColor(h3.linear([0, 0, 0]), 1);
        await s.compositor.prepare(s.scene);
        h3.frames(s, 1);
        res.push(Array.from(h3.readTarget(s)));
        vol.dispose();
        s.renderer.dispose();
      }
      return { want, res };
    }, N);
    out.res.forEach((got, i) => {
      savePng(`transform-${i}`, got);
      expect(meanRgbDiff(got, out.want)).toBeLessThan(2e-4);
    });
  });

  it('an opaque mesh in front of the whole volume shows only the mesh (every renderer)', async () => {
    const out = await three().run(async (h3, n) => {
      const { THREE, eam, mcrt, mip, iso, vt3 } = (window as any).ref;
      const make: Record<string, () => unknown> = {
        eam: () => new eam.EamRenderer(),
        mcrt: () => new mcrt.McrtRenderer(),
        mip: () => new mip.MipRenderer(),
        iso: () => new iso.IsoRenderer(),
      };
      const res: Record<string, number[]> = {};
      for (const r of Object.keys(make)) {
        const s = h3.setup(n);
        const vol = new vt3.VptVolume({
          renderer: make[r](),
          scene: h3.vptScene('cube', 8, [1, 1, 1], 1, 20, [1, 1, 1]),
          iterationsPerFrame: 4,
        });
        s.scene.add(vol);
        const plane = new THREE.Mesh(
          new THREE.PlaneGeometry(3, 3),
          new THREE.MeshBasicMaterial({ color: h3.linear([0.9, 0.1, 0.3]) }),
        );
        plane.position.z = 0.8;
        s.scene.add(plane);
        await s.compositor.prepare(s.scene);
        h3.frames(s, 2);
        res[r] = Array.from(h3.readTarget(s));
        vol.dispose();
        s.renderer.dispose();
      }
      return res;
    }, N);
    for (const r of ['eam', 'mcrt', 'mip', 'iso']) {
      savePng(`front-${r}`, out[r]);
      // The mesh's colour exactly, on every pixel.
      for (let i = 0; i < N * N; i++) {
        expect(out[r][4 * i]).toBeCloseTo(0.9, 6);
        expect(out[r][4 * i + 1]).toBeCloseTo(0.1, 6);
        expect(out[r][4 * i + 2]).toBeCloseTo(0.3, 6);
      }
    }
  });

  it('a mesh inside a homogeneous cube is attenuated by its transmittance (EAM: exact; MCRT: unbiased)', async () => {
    const m = [0.1, 0.5, 0.9];
    const color = [1, 0.5, 0.25];
    const sigma = 2;
    const out = await three().run(
      async (h3, n, m, color, sigma) => {
        const { THREE, eam, mcrt, vt3 } = (window as any).ref;
        const res: Record<string, number[]> = {};
        for (const r of ['eam', 'mcrt']) {
          const s = h3.setup(n);
          // MCRT: a purely absorbing cube (albedo 0), so the composite is T · mesh in expectation.
          const vscene = h3.vptScene('cube', 8, r === 'eam' ? color : [0, 0, 0], 1, sigma, [0.5, 0.5, 0.5]);
          const vol = new vt3.VptVolume({
            renderer: r === 'eam' ? new eam.EamRenderer() : new mcrt.McrtRenderer(),
            scene: vscene,
            iterationsPerFrame: r === 'eam' ? 16 : 64,
          });
          s.scene.add(vol);
          // A plane through the cube's centre, facing the camera.
          const plane = new THREE.Mesh(
            new THREE.PlaneGeometry(3, 3),
            new THREE.MeshBasicMaterial({ color: h3.linear(m) }),
          );
          s.scene.add(plane);
          s.renderer.setClearColor(h3.linear([0, 0, 0]), 1);
          await s.compositor.prepare(s.scene);
          h3.frames(s, r === 'eam' ? 1 : 4);
          res[r] = Array.from(h3.readTarget(s));
          vol.dispose();
          s.renderer.dispose();
        }
        return res;
      },
      N,
      m,
      color,
      sigma,
    );
    // CPU expectation along each pixel-centre ray from (0, 0, 2): the ray crosses the front face
    // z = 0.5 and ends on the plane z = 0 inside the box, a path of 0.5 / |d_z| through the medium.
    const t = Math.tan((20 * Math.PI) / 180);
    const expectEam: number[] = [];
    const gotEam: number[] = [];
    let sumMcrt = 0;
    let sumWant = 0;
    let sumVar = 0;
    for (let y = 0; y < N; y++) {
      for (let x = 0; x < N; x++) {
        const sx = ((2 * (x + 0.5)) / N - 1) * t;
        const sy = (1 - (2 * (y + 0.5)) / N) * t;
        // Inside the box at both ends (front face at distance 1.5, plane at 2).
        if (Math.abs(sx * 2) > 0.48 || Math.abs(sy * 2) > 0.48) continue;
        const len = 0.5 * Math.hypot(sx, sy, 1);
        const T = Math.exp(-sigma * len);
        const i = 4 * (y * N + x);
        for (let c = 0; c < 3; c++) {
          expectEam.push(color[c] * (1 - T) + T * m[c]);
          gotEam.push(out.eam[i + c]);
        }
        sumMcrt += out.mcrt[i + 2];
        sumWant += T * m[2];
        sumVar += (T * (1 - T) * m[2] * m[2]) / 256;
      }
    }
    savePng('inside-eam', out.eam);
    savePng('inside-mcrt', out.mcrt);
    expect(gotEam.length).toBeGreaterThan(300);
    // Jittered rays within a pixel differ slightly from its centre ray: 2e-3.
    gotEam.forEach((g, i) => expect(Math.abs(g - expectEam[i])).toBeLessThan(2e-3));
    // MCRT: the mean over the pixels, 256 paths each, within 4 standard deviations.
    expect(Math.abs(sumMcrt - sumWant)).toBeLessThan(4 * Math.sqrt(sumVar));
  });

  it('moving the object or the camera restarts accumulation', async () => {
    const counts = await three().run(async (h3, n) => {
      const { eam, vt3 } = (window as any).ref;
      const s = h3.setup(n);
      const vol = new vt3.VptVolume({
        renderer: new eam.EamRenderer(),
        scene: h3.vptScene('blob', 16, [1, 1, 1], 1, 8, [0, 0, 0]),
        iterationsPerFrame: 2,
      });
      s.scene.add(vol);
      await s.compositor.prepare(s.scene);
      const c: number[] = [];
      const frame = () => {
        h3.frames(s, 1);
        c.push(vol.sampleCount);
      };
      frame();
      frame();
      frame(); // 2, 4, 6
      vol.position.x = 0.1;
      frame(); // 2
      frame(); // 4
      s.camera.position.set(0.2, 0, 2);
      s.camera.lookAt(0, 0, 0);
      s.camera.updateMatrixWorld();
      frame(); // 2
      vol.rotation.y = 0.3;
      frame(); // 2
      vol.scale.set(1, 1.5, 1);
      frame(); // 2
      frame(); // 4
      vol.dispose();
      s.renderer.dispose();
      return c;
    }, N);
    expect(counts).toEqual([2, 4, 6, 2, 4, 2, 2, 2, 4]);
  });

  it('leaves three.js’s state intact: a three-only frame after vpt drew equals one before', async () => {
    const out = await three().run(async (h3, n) => {
      const { THREE, eam, vt3 } = (window as any).ref;
      const s = h3.setup(n);
      // A three-only scene that exercises textures, lighting, blending and depth.
      const plain = new THREE.Scene();
      plain.background = h3.linear([0.1, 0.2, 0.3]);
      const tex = new THREE.DataTexture(
        new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]),
        2,
        2,
      );
      tex.needsUpdate = true;
      plain.add(new THREE.Mesh(new THREE.BoxGeometry(0.8, 0.8, 0.8), new THREE.MeshStandardMaterial({ map: tex })));
      plain.add(new THREE.DirectionalLight(0xffffff, 2));
      const glass = new THREE.Mesh(
        new THREE.SphereGeometry(0.3),
        new THREE.MeshBasicMaterial({ color: 0x00ffff, transparent: true, opacity: 0.5 }),
      );
      glass.position.set(0.2, 0.2, 0.6);
      plain.add(glass);
      const rt = new THREE.WebGLRenderTarget(n, n, { type: THREE.FloatType });
      const read = () => {
        s.renderer.setRenderTarget(rt);
        s.renderer.render(plain, s.camera);
        s.renderer.setRenderTarget(null);
        const px = new Float32Array(n * n * 4);
        s.renderer.readRenderTargetPixels(rt, 0, 0, n, n, px);
        return Array.from(px);
      };
      const before = read();
      // The volume scene: vpt draws on the same context (volume, mesh, transparent mesh).
      const vol = new vt3.VptVolume({
        renderer: new eam.EamRenderer(),
        scene: h3.vptScene('blob', 16, [1, 1, 1], 1, 8, [0, 0, 0]),
        iterationsPerFrame: 2,
      });
      s.scene.add(vol);
      s.scene.add(glass.clone());
      await s.compositor.prepare(s.scene);
      h3.frames(s, 3);
      const after = read();
      const volumeImage = Array.from(h3.readTarget(s));
      vol.dispose();
      s.renderer.dispose();
      return { before, after, volumeImage };
    }, N);
    savePng('state-plain', out.before);
    savePng('state-volume', out.volumeImage);
    expect(out.after).toEqual(out.before);
  });

  it('writes a representative depth: a transparent mesh in front of the medium shows, behind it is hidden (EAM, MCRT)', async () => {
    // A sphere (radius 0.35) of dense medium in the unit box: the box's front face is at
    // z = 0.5, the medium's at about 0.35. Transparent planes are drawn after the volume and
    // tested against the depth it wrote; an opaque plane behind the box is composited by the
    // volume's transmittance.
    const green = [0.1, 0.9, 0.2];
    const out = await three().run(
      async (h3, n, green) => {
        const { THREE, eam, mcrt, vt3 } = (window as any).ref;
        const res: Record<string, Record<string, number[]>> = {};
        for (const r of ['eam', 'mcrt']) {
          res[r] = {};
          for (const [name, z, transparent] of [
            ['none', null, false],
            ['front', 0.42, true],
            ['behind', 0.2, true],
            ['opaque', -0.7, false],
          ] as const) {
            const s = h3.setup(n);
            const vol = new vt3.VptVolume({
              renderer: r === 'eam' ? new eam.EamRenderer() : new mcrt.McrtRenderer(),
              scene: {
                ...h3.vptScene('sphere', 32, [1, 0.6, 0.3], 1, 40, [0, 0, 0]),
                // Opacity rising with the value: clear outside the sphere.
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
                new THREE.MeshBasicMaterial(
                  transparent
                    ? { color: h3.linear(green), transparent: true, opacity: 0.5 }
                    : { color: h3.linear(green) },
                ),
              );
              plane.position.z = z;
              s.scene.add(plane);
            }
            s.renderer.setClearColor(h3.linear([0, 0, 0]), 1);
            await s.compositor.prepare(s.scene);
            h3.frames(s, 2);
            res[r][name] = Array.from(h3.readTarget(s));
            vol.dispose();
            s.renderer.dispose();
          }
        }
        return res;
      },
      N,
      green,
    );
    // Pixel-centre rays from (0, 0, 2): which cross the sphere, which pass the box without meeting it.
    const t = Math.tan((20 * Math.PI) / 180);
    for (const r of ['eam', 'mcrt']) {
      const o = out[r];
      for (const k of Object.keys(o)) savePng(`depth-${r}-${k}`, o[k]);
      let centre = 0;
      let clear = 0;
      for (let y = 0; y < N; y++) {
        for (let x = 0; x < N; x++) {
          const sx = ((2 * (x + 0.5)) / N - 1) * t;
          const sy = (1 - (2 * (y + 0.5)) / N) * t;
          const d = [sx, sy, -1];
          const len = Math.hypot(...d);
          // Closest approach of the ray to the sphere's centre.
          const along = (2 * 1) / len;
          const miss = Math.hypot((sx * along) / len, (sy * along) / len, 2 - along / len);
          const i = 4 * (y * N + x);
          if (miss < 0.15) {
            centre++;
            for (let c = 0; c < 3; c++) {
              // In front of the medium (behind the box entry): blended over the volume.
              expect(Math.abs(o.front[i + c] - (0.5 * green[c] + 0.5 * o.none[i + c]))).toBeLessThan(1e-5);
              // Behind the medium's front: hidden.
              expect(o.behind[i + c]).toBeCloseTo(o.none[i + c], 6);
              // Opaque and behind an opaque medium: hidden (T = exp(−40 · 0.5) at most).
              expect(Math.abs(o.opaque[i + c] - o.none[i + c])).toBeLessThan(1e-4);
            }
          }
          // Through the box (x, y within ±0.45 at z = ±0.5) but farther than 0.4 from the centre.
          const inBox = [1.5, 2.5].every((dz) => Math.abs(sx * dz) < 0.45 && Math.abs(sy * dz) < 0.45);
          if (inBox && miss > 0.4) {
            clear++;
            for (let c = 0; c < 3; c++) {
              // (Almost) no medium there: the opaque plane shows unattenuated, the transparent one
              // blended over the background (the sphere's filtered edge leaves a < 0.01).
              expect(Math.abs(o.opaque[i + c] - green[c])).toBeLessThan(0.01);
              expect(Math.abs(o.behind[i + c] - 0.5 * green[c])).toBeLessThan(0.01);
            }
          }
        }
      }
      expect(centre).toBeGreaterThan(10);
      expect(clear).toBeGreaterThan(10);
    }
  });

  it('MIP with a mesh inside: the maximum only over the ray in front of the mesh (CPU expectation)', async () => {
    // The ramp volume (value rising along its x axis) turned 90° about y, so its value rises
    // away from the camera; a plane at z = 0 cuts it. The maximum along each pixel-centre ray
    // in front of the plane is the ramp's value where the ray ends (at the plane or where it
    // leaves the box), computed here; the composite is max + (1 − max) · mesh (a = max).
    const size = 16;
    const m = [0.2, 0.4, 0.6];
    const out = await three().run(
      async (h3, n, size, m) => {
        const { THREE, mip, vt3 } = (window as any).ref;
        const s = h3.setup(n);
        const vol = new vt3.VptVolume({
          renderer: new mip.MipRenderer(),
          scene: h3.vptScene('ramp', size, [1, 1, 1], 1, 1, [0, 0, 0]),
          iterationsPerFrame: 16,
        });
        vol.rotation.y = Math.PI / 2;
        s.scene.add(vol);
        s.scene.add(
          new THREE.Mesh(new THREE.PlaneGeometry(3, 3), new THREE.MeshBasicMaterial({ color: h3.linear(m) })),
        );
        s.renderer.setClearColor(h3.linear([0, 0, 0]), 1);
        await s.compositor.prepare(s.scene);
        h3.frames(s, 4);
        const img = Array.from(h3.readTarget(s));
        vol.dispose();
        s.renderer.dispose();
        return img;
      },
      N,
      size,
      m,
    );
    savePng('mip-inside', out);
    const t = Math.tan((20 * Math.PI) / 180);
    const ramp = (lx: number) => Math.min(1, Math.max(0, ((lx + 0.5) * size - 0.5) / (size - 1)));
    let n = 0;
    for (let y = 0; y < N; y++) {
      for (let x = 0; x < N; x++) {
        const d = [((2 * (x + 0.5)) / N - 1) * t, (1 - (2 * (y + 0.5)) / N) * t, -1];
        // Ray (0, 0, 2) + s·d against the box |x|, |y|, |z| ≤ 0.5, ended at the plane z = 0.
        let t0 = 0;
        let t1 = 2; // the plane: z = 2 − s
        const o = [0, 0, 2];
        for (let a = 0; a < 3; a++) {
          const ta = (-0.5 - o[a]) / d[a];
          const tb = (0.5 - o[a]) / d[a];
          t0 = Math.max(t0, Math.min(ta, tb));
          t1 = Math.min(t1, Math.max(ta, tb));
        }
        const i = 4 * (y * N + x);
        if (t0 >= t1 - 0.05) continue; // misses the box, or grazes it
        n++;
        // World z at the end → the volume's local x = −z (turned 90° about y); the value rises along the ray.
        const v = ramp(-(2 - t1));
        for (let c = 0; c < 3; c++) expect(Math.abs(out[i + c] - (v + (1 - v) * m[c]))).toBeLessThan(0.03);
      }
    }
    expect(n).toBeGreaterThan(300);
  });

  it('ISO with a mesh inside: the mesh where it is in front of the surface, the surface where it is behind', async () => {
    // The turned ramp (as above) with isoValue 0.7: the surface is the plane where the ramp
    // reaches 0.7, world z = −((0.7 · 15 + 0.5) / 16 − 0.5) = −0.1875.
    const size = 16;
    const m = [0.2, 0.4, 0.6];
    const zSurface = -((0.7 * (size - 1) + 0.5) / size - 0.5);
    const planes = [zSurface + 0.06, zSurface - 0.06, -0.45];
    const out = await three().run(
      async (h3, n, size, m, planes) => {
        const { THREE, iso, vt3 } = (window as any).ref;
        const res: number[][] = [];
        for (const z of planes) {
          const s = h3.setup(n);
          const vol = new vt3.VptVolume({
            renderer: new iso.IsoRenderer({ surfaces: [{ value: 0.7, color: [1, 1, 1] }] }),
            scene: h3.vptScene('ramp', size, [1, 1, 1], 1, 1, [0, 0, 0]),
            iterationsPerFrame: 4,
          });
          vol.rotation.y = Math.PI / 2;
          s.scene.add(vol);
          const plane = new THREE.Mesh(
            new THREE.PlaneGeometry(3, 3),
            new THREE.MeshBasicMaterial({ color: h3.linear(m) }),
          );
          plane.position.z = z;
          s.scene.add(plane);
          s.renderer.setClearColor(h3.linear([0, 0, 0]), 1);
          await s.compositor.prepare(s.scene);
          h3.frames(s, 2);
          res.push(Array.from(h3.readTarget(s)));
          vol.dispose();
          s.renderer.dispose();
        }
        return res;
      },
      N,
      size,
      m,
      planes,
    );
    const [front, behind, far] = out;
    savePng('iso-front', front);
    savePng('iso-behind', behind);
    const t = Math.tan((20 * Math.PI) / 180);
    let n = 0;
    for (let y = 0; y < N; y++) {
      for (let x = 0; x < N; x++) {
        const sx = ((2 * (x + 0.5)) / N - 1) * t;
        const sy = (1 - (2 * (y + 0.5)) / N) * t;
        const i = 4 * (y * N + x);
        // The plane in front of the surface: the mesh's colour, exactly, on every pixel.
        for (let c = 0; c < 3; c++) expect(front[i + c]).toBeCloseTo(m[c], 5);
        // Where the ray meets the surface inside the box (with a margin for jitter), the plane
        // behind it is hidden: the image equals the one with the plane far behind.
        const at = 2 - zSurface;
        if (Math.abs(sx * at) > 0.45 || Math.abs(sy * at) > 0.45 || Math.abs(sx * 1.5) > 0.45) continue;
        n++;
        for (let c = 0; c < 3; c++) expect(Math.abs(behind[i + c] - far[i + c])).toBeLessThan(1e-5);
        expect(Math.abs(behind[i] - m[0]) + Math.abs(behind[i + 2] - m[2])).toBeGreaterThan(0.05);
      }
    }
    expect(n).toBeGreaterThan(200);
  });

  // The cost per frame over plain vpt (docs/benchmarks.md, "three.js"): interleaved rounds of
  // 20 frames, one iteration each, synchronised by a 1-pixel read. Off by default (minutes on
  // SwiftShader): VPT_THREE_BENCH=64 (the size) runs it and prints the figures.
  it.skipIf(!process.env.VPT_THREE_BENCH)('frame cost: plain vpt, @vpt/three, vpt on its own context', async () => {
    const size = Number(process.env.VPT_THREE_BENCH);
    const res = await three().run(async (h3, size) => {
      const { THREE, core, eam, vt3 } = (window as any).ref;
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
      const sync = (gl: WebGL2RenderingContext) => gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      // A: plain vpt on its own canvas (iterate + HDR image).
      const ca = document.createElement('canvas');
      const A = await core.RenderContext.create({
        backend: 'webgl2',
        canvas: ca,
        width: size,
        height: size,
        renderer: new eam.EamRenderer(),
      });
      A.setScene({ ...vscene, camera: cam });
      const ga = ca.getContext('webgl2')!;
      // B: the same volume in a three.js scene with a lit cylinder, on three's context.
      const s = h3.setup(size);
      s.compositor.dispose();
      s.compositor = new vt3.VptCompositor(s.renderer);
      const mesh = new THREE.Mesh(new THREE.CylinderGeometry(0.05, 0.05, 1.4), new THREE.MeshStandardMaterial());
      mesh.rotation.z = 1;
      s.scene.add(mesh, new THREE.DirectionalLight(0xffffff, 2));
      const vol = new vt3.VptVolume({ renderer: new eam.EamRenderer(), scene: vscene, maxSamples: 1e9 });
      s.scene.add(vol);
      await s.compositor.prepare(s.scene);
      const gb = s.renderer.getContext();
      // C: vpt on its own context, its HDR image read back and uploaded into three (no depth).
      const cc = document.createElement('canvas');
      const C = await core.RenderContext.create({
        backend: 'webgl2',
        canvas: cc,
        width: size,
        height: size,
        renderer: new eam.EamRenderer(),
      });
      C.setScene({ ...vscene, camera: cam });
      const tex = new THREE.DataTexture(
        new Float32Array(size * size * 4),
        size,
        size,
        THREE.RGBAFormat,
        THREE.FloatType,
      );
      const quad = new THREE.Mesh(
        new THREE.PlaneGeometry(2, 2),
        new THREE.ShaderMaterial({
          uniforms: { t: { value: tex } },
          transparent: true,
          depthTest: false,
          depthWrite: false,
          blending: THREE.CustomBlending,
          blendSrc: THREE.OneFactor,
          blendDst: THREE.OneMinusSrcAlphaFactor,
          vertexShader:
            'varying vec2 vUv; void main() { vUv = vec2(uv.x, 1.0 - uv.y); gl_Position = vec4(position.xy, 0.0, 1.0); }',
          fragmentShader: 'uniform sampler2D t; varying vec2 vUv; void main() { gl_FragColor = texture2D(t, vUv); }',
        }),
      );
      quad.frustumCulled = false;
      const qcam = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
      const frames: Record<string, () => Promise<void> | void> = {
        vpt: () => {
          A.iterate(1);
          A.renderImage();
          sync(ga);
        },
        three: () => {
          s.compositor.render(s.scene, s.camera);
          sync(gb);
        },
        threeAlone: () => {
          vol.visible = false;
          s.compositor.render(s.scene, s.camera);
          vol.visible = true;
          sync(gb);
        },
        ownContext: async () => {
          C.iterate(1);
          C.renderImage();
          tex.image.data.set(await C.readHDR());
          tex.needsUpdate = true;
          vol.visible = false;
          s.renderer.render(s.scene, s.camera);
          s.renderer.autoClear = false;
          s.renderer.render(quad, qcam);
          s.renderer.autoClear = true;
          vol.visible = true;
          sync(gb);
        },
      };
      const time = async (f: () => Promise<void> | void, n: number) => {
        const t0 = performance.now();
        for (let i = 0; i < n; i++) await f();
        return (performance.now() - t0) / n;
      };
      const out: Record<string, number[]> = {};
      for (const [k, f] of Object.entries(frames)) {
        await time(f, 5);
        out[k] = [];
      }
      for (let r = 0; r < 7; r++) for (const [k, f] of Object.entries(frames)) out[k].push(await time(f, 20));
      A.dispose();
      C.dispose();
      vol.dispose();
      s.renderer.dispose();
      return out;
    }, size);
    const med = (a: number[]) => [...a].sort((x, y) => x - y)[a.length >> 1];
    const ratio = (x: number[]) => med(x.map((v, i) => v / res.vpt[i]));
    console.log(
      `${size}²: plain vpt ${med(res.vpt).toFixed(1)} ms/frame; @vpt/three ${med(res.three).toFixed(1)} ms (× ${ratio(res.three).toFixed(2)}); ` +
        `three alone ${med(res.threeAlone).toFixed(1)} ms; own context + read-back ${med(res.ownContext).toFixed(1)} ms (× ${ratio(res.ownContext).toFixed(2)})`,
    );
    expect(res.three.every(Number.isFinite)).toBe(true);
  });
});
