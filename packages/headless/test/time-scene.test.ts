import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { parseTimeRange, stepFileName } from '../src/cli/args.js';
import { selectTimeStep } from '../src/scene-description.js';
import { resolveSceneFiles } from '../src/scene-files.js';
import { validateSceneDescription } from '../src/validate-description.js';

describe('vpt-render --time', () => {
  it('parses a step or an inclusive range, refusing bad ones by name', () => {
    expect(parseTimeRange('3')).toEqual({ first: 3, last: 3 });
    expect(parseTimeRange('0:4')).toEqual({ first: 0, last: 4 });
    expect(() => parseTimeRange('4:2')).toThrow(/--time: the range 4:2 ends before it starts/);
    expect(() => parseTimeRange('a:b')).toThrow(/--time: expected a step A or a range A:B/);
    expect(() => parseTimeRange('-1')).toThrow(/--time/);
  });

  it('numbers the output files', () => {
    expect(stepFileName('out/frame-%03d.png', 7, true)).toBe('out/frame-007.png');
    expect(stepFileName('out/f%d.png', 12, false)).toBe('out/f12.png');
    expect(stepFileName('out/frame.png', 2, true)).toBe('out/frame-002.png');
    expect(stepFileName('out/frame.png', 2, false)).toBe('out/frame.png');
    expect(stepFileName('out.d/frame', 1, true)).toBe('out.d/frame-001');
  });
});

describe('the scene file\'s "time"', () => {
  it("moves the step into the volume: a list entry, a file's or a store's time", () => {
    const list = { time: 1, volume: { timeSeries: ['a.nii', ['b.nhdr', 'b.raw']], valueRange: [0, 9] } };
    expect(selectTimeStep(list as never)).toEqual({ volume: { file: ['b.nhdr', 'b.raw'], valueRange: [0, 9] } });
    expect(selectTimeStep({ volume: { timeSeries: ['a.nii'] } } as never)).toEqual({ volume: { file: 'a.nii' } });
    expect(selectTimeStep({ time: 2, volume: { file: 'x.nii' } })).toEqual({ volume: { file: 'x.nii', time: 2 } });
    expect(selectTimeStep({ time: 2, volume: { zarr: 's.zarr' } })).toEqual({ volume: { zarr: 's.zarr', time: 2 } });
    expect(() => selectTimeStep({ ...list, time: 2 } as never)).toThrow(
      /"time" 2 is past the end of volume.timeSeries \(2 steps, 0 to 1\)/,
    );
    expect(() => selectTimeStep({ time: 1, volume: { procedural: 'blob' } })).toThrow(/not a time series/);
    expect(selectTimeStep({ time: 0, volume: { procedural: 'blob' } })).toEqual({ volume: { procedural: 'blob' } });
  });

  it('is checked with the other fields, and a list step past the end is a typed error before any browser', () => {
    expect(() => validateSceneDescription({ time: -1 })).toThrow(/time/);
    expect(() => validateSceneDescription({ volume: { timeSeries: [] } })).toThrow(
      /volume.timeSeries: must be a non-empty list/,
    );
    expect(() => validateSceneDescription({ volume: { timeSeries: ['a', 3] } })).toThrow(/volume.timeSeries\[1\]/);
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-time-scene-'));
    try {
      fs.writeFileSync(path.join(dir, 'a.nii'), new Uint8Array(400));
      const d = validateSceneDescription({ time: 3, volume: { timeSeries: ['a.nii'] } });
      expect(() => resolveSceneFiles(d, dir)).toThrow(expect.objectContaining({ code: 'invalid-scene' }));
      const ok = resolveSceneFiles(validateSceneDescription({ time: 0, volume: { timeSeries: ['a.nii'] } }), dir);
      expect(ok.volume).toEqual({ file: path.join(dir, 'a.nii') });
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
  });
});
