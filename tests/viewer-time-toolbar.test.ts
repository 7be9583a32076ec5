import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { useViewerPage } from './helpers/viewer-page.js';
import { uint8Ball } from './helpers/uint8-ball.js';

// The viewer's time toolbar (time-player.ts, lazy) and a `src` that lists several files (URLs
// separated by whitespace) as a time series: the toolbar shows only for a series; its button toggles `playing`, its slider sets
// `time`; three raw + sidecar files play as three steps, each step's image that of its file
// loaded alone in another viewer.
const viewer = useViewerPage();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-viewer-time-toolbar-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const D = 10;
/** Step k: a ball whose centre moves along y with k (a different image per step). */
function ball(k: number): Uint8Array {
  return uint8Ball(D, [5, 2 + 2.5 * k, 5], 3.5);
}

describe('<vpt-viewer> time toolbar and a src list', () => {
  it('a src of 3 URLs plays 3 files as 3 steps equal to each file alone; the button toggles playing, the slider sets time', async () => {
    for (let k = 0; k < 3; k++) {
      fs.writeFileSync(path.join(dir, `step${k}.raw`), ball(k));
      fs.writeFileSync(
        path.join(dir, `step${k}.json`),
        JSON.stringify({ file: `step${k}.raw`, dims: [D, D, D], voxel_type: 'uint8', spacing: [1, 1, 1] }),
      );
    }
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const attrs = {
        renderer: 'mip',
        backend: 'webgl2',
        panels: 'export',
        'max-samples': '2',
        'transfer-function': 'grayscale',
      };
      const urls = [0, 1, 2].map((k) => `${base}step${k}.json`);
      // Each file alone: its image, and no time toolbar for one volume.
      const alone: number[][] = [];
      let barAlone = true;
      for (const u of urls) {
        const a = vt.create({ ...attrs, src: u });
        await vt.next(a, 'load');
        await vt.converged(a);
        alone.push(await vt.ldr(a));
        await vt.frames(2);
        barAlone &&= !!a.shadowRoot.querySelector('[part~="timebar"]');
        a.remove();
      }
      const el = vt.create({ ...attrs, src: urls.join(' \n ') });
      await vt.next(el, 'load');
      await vt.converged(el);
      const steps = el.timeSteps;
      // The toolbar lands with the lazy player.
      let button: HTMLButtonElement | null = null;
      for (let i = 0; i < 200 && !button; i++) {
        await vt.frames(1);
        button = el.shadowRoot.querySelector('[part~="time-play"]');
      }
      const slider = el.shadowRoot.querySelector('[part~="time-slider"]') as HTMLInputElement | null;
      const sliderMax = slider?.max;
      const images: number[][] = [await vt.ldr(el)];
      const readouts: (string | null)[] = [vt.shadowText(el, '[part~="time-readout"]')];
      // The slider sets time: steps 1 and 2, each shown once read.
      for (const k of [1, 2]) {
        const changed = vt.next(el, 'change');
        slider!.value = String(k);
        slider!.dispatchEvent(new Event('input', { bubbles: true }));
        await changed;
        await vt.converged(el);
        images.push(await vt.ldr(el));
        await vt.frames(2);
        readouts.push(vt.shadowText(el, '[part~="time-readout"]'));
      }
      const timeAfterSlider = el.time;
      // The button toggles playing; playback walks the three steps in order, looping.
      const played: number[] = [];
      el.addEventListener(
        'vpt-change',
        (e: CustomEvent) => e.detail.property === 'time' && played.push(e.detail.value),
      );
      el.setAttribute('fps', '30');
      button!.click();
      await vt.frames(1);
      const playingAfterClick = el.playing;
      const attrAfterClick = el.hasAttribute('playing');
      const labelPlaying = button!.textContent!.trim();
      const t0 = performance.now();
      while (played.length < 4 && performance.now() - t0 < 60000) await vt.frames(2);
      button!.click();
      await vt.frames(1);
      const playingAfterSecond = el.playing;
      const labelPaused = button!.textContent!.trim();
      el.remove();
      return {
        alone,
        barAlone,
        steps,
        hasButton: !!button,
        sliderMax,
        images,
        readouts,
        timeAfterSlider,
        played,
        playingAfterClick,
        attrAfterClick,
        labelPlaying,
        playingAfterSecond,
        labelPaused,
        urls,
      };
    }, base);
    expect(r.barAlone).toBe(false);
    expect(r.steps).toBe(3);
    expect(r.hasButton).toBe(true);
    expect(r.sliderMax).toBe('2');
    // The three files differ, and each step's image is its file's.
    expect(r.alone[1]).not.toEqual(r.alone[0]);
    expect(r.alone[2]).not.toEqual(r.alone[1]);
    for (let k = 0; k < 3; k++) expect(r.images[k]).toEqual(r.alone[k]);
    expect(r.readouts).toEqual(['1 / 3', '2 / 3', '3 / 3']);
    expect(r.timeAfterSlider).toBe(2);
    expect(r.playingAfterClick).toBe(true);
    expect(r.attrAfterClick).toBe(true);
    expect(r.labelPlaying).toBe('Pause');
    expect(r.played.slice(0, 4)).toEqual([0, 1, 2, 0]);
    expect(r.playingAfterSecond).toBe(false);
    expect(r.labelPaused).toBe('Play');
    expect(viewer().errors).toEqual([]);
  });
});
