import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { useViewerPage } from './helpers/viewer-page.js';
import { uint8Ball } from './helpers/uint8-ball.js';

// <vpt-viewer time fps playing> on a 4D NIfTI: the `time` attribute shows that step (the
// image of the step's own 3D file), `vpt-change` says so, and playback walks the steps in
// order, looping, until paused.
const viewer = useViewerPage();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-viewer-time-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const D = 10;
/** Step k: a ball whose centre moves along x with k. */
function ball(k: number): Uint8Array {
  return uint8Ball(D, [2 + 2 * k, 5, 5], 3.5);
}

/** A NIfTI-1 file (uint8, 1 mm) of these volumes along dim[4] (one volume: a 3D file). */
function nifti(volumes: Uint8Array[]): Uint8Array {
  const out = new Uint8Array(352 + volumes.length * D ** 3);
  const v = new DataView(out.buffer);
  v.setInt32(0, 348, true);
  const dims = volumes.length > 1 ? [4, D, D, D, volumes.length, 1, 1, 1] : [3, D, D, D, 1, 1, 1, 1];
  dims.forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
  v.setInt16(70, 2, true);
  v.setInt16(72, 8, true);
  [1, 1, 1, 1, 0.2, 1, 1, 1].forEach((p, i) => v.setFloat32(76 + 4 * i, p, true));
  v.setFloat32(108, 352, true);
  out[123] = 2 | 8;
  out.set([0x6e, 0x2b, 0x31, 0], 344);
  volumes.forEach((vol, k) => out.set(vol, 352 + k * D ** 3));
  return out;
}

describe('<vpt-viewer time>', () => {
  it('time shows that step, play walks the steps in order and loops, pause stops', async () => {
    const steps = [0, 1, 2].map(ball);
    fs.writeFileSync(path.join(dir, 'four.nii'), nifti(steps));
    fs.writeFileSync(path.join(dir, 'step2.nii'), nifti([steps[2]]));
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const attrs = {
        renderer: 'mip',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '2',
        'transfer-function': 'grayscale',
      };
      const el = vt.create({ ...attrs, src: `${base}four.nii` });
      await vt.next(el, 'load');
      await vt.converged(el);
      const first = await vt.ldr(el);
      const stepsSeen = el.timeSteps;
      el.setAttribute('time', '2');
      const change = await vt.next(el, 'change');
      await vt.converged(el);
      const second = await vt.ldr(el);
      const alone = vt.create({ ...attrs, src: `${base}step2.nii` });
      await vt.next(alone, 'load');
      await vt.converged(alone);
      const aloneImage = await vt.ldr(alone);
      alone.remove();
      // Playback: every step in turn, looping past the last.
      const played: number[] = [];
      el.addEventListener(
        'vpt-change',
        (e: CustomEvent) => e.detail.property === 'time' && played.push(e.detail.value),
      );
      el.setAttribute('fps', '30');
      el.play();
      const t0 = performance.now();
      while (played.length < 5 && performance.now() - t0 < 60000) await vt.frames(2);
      el.pause();
      const stoppedAt = played.length;
      await new Promise((res) => setTimeout(res, 300));
      const after = played.length;
      const reflected = el.getAttribute('time');
      el.remove();
      return { first, second, aloneImage, change, stepsSeen, played, stoppedAt, after, reflected, timeNow: el.time };
    }, base);
    expect(r.stepsSeen).toBe(3);
    expect(r.change).toEqual({ property: 'time', value: 2 });
    expect(r.second).not.toEqual(r.first);
    expect(r.second).toEqual(r.aloneImage);
    expect(r.played.slice(0, 5)).toEqual([0, 1, 2, 0, 1]);
    expect(r.after).toBe(r.stoppedAt);
    expect(r.reflected).toBe(String(r.timeNow));
    expect(viewer().errors).toEqual([]);
  });
});
