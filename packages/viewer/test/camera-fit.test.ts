import { describe, expect, it } from 'vitest';
import { anatomicalFrame, fitCamera } from '../src/camera-fit.js';
import { autoTransferFunction, defaultRendererParams } from '../src/defaults.js';
import { createVolume } from '@vpt/core';

const box = { dims: [64, 64, 64] as [number, number, number], spacing: [1, 1, 1] as [number, number, number] };
const dot = (a: number[], b: number[]) => a.reduce((s, x, i) => s + x * b[i], 0);

describe('default camera', () => {
  it("puts anatomical superior up from an orientation matrix (RAS or LPS) or a sidecar's axis codes, +y without one", () => {
    expect(fitCamera(box).up).toEqual([0, 1, 0]);
    // RAS identity: superior is +z, the camera sits in front (+y = anterior).
    const ras = fitCamera({ ...box, orientation: [1, 0, 0, 0, 1, 0, 0, 0, 1], meta: { space: 'RAS' } });
    expect(ras.up).toEqual([0, 0, 1]);
    expect(ras.position[1]).toBeGreaterThan(Math.abs(ras.position[0]));
    // LPS identity (DICOM): +y is posterior, so the camera sits at −y; superior still +z.
    const lps = fitCamera({ ...box, orientation: [1, 0, 0, 0, 1, 0, 0, 0, 1], meta: { space: 'LPS' } });
    expect(lps.up).toEqual([0, 0, 1]);
    expect(lps.position[1]).toBeLessThan(-Math.abs(lps.position[0]));
    // The bundled head: x toward the back, y toward the neck, z to the right.
    const head = fitCamera({ ...box, meta: { axisCodes: 'PIR' } });
    expect(head.up).toEqual([0, -1, 0]);
    expect(head.position[0]).toBeLessThan(0); // in front of the face (x = 0 is the face)
    // The camera looks at the centre from outside the bounding sphere, up perpendicular enough to the view.
    const dir = head.position.map((x) => x / Math.hypot(...head.position));
    expect(Math.abs(dot(dir, head.up))).toBeLessThan(0.5);
    expect(anatomicalFrame({ ...box, meta: { axisCodes: 'PPR' } })).toBeNull();
  });
});

describe('automatic transfer function', () => {
  it('is clear below the foreground median and opaque at its 99.5th percentile; iso gets a surface between', () => {
    // Values 0..99 (0 is background), uniformly: quantiles of 1..99.
    const data = new Uint8Array(100 * 10);
    for (let i = 0; i < data.length; i++) data[i] = i % 100;
    const v = createVolume([10, 10, 10], 'uint8', data);
    v.valueRange = [0, 99];
    const tf = autoTransferFunction(v);
    if (tf.dimensions !== '1d') throw new Error('1d expected');
    expect(tf.points.map((p) => p.opacity)).toEqual([0, 0.15, 1]);
    expect(tf.points[0].value).toBeGreaterThan(0.45);
    expect(tf.points[0].value).toBeLessThan(0.56);
    expect(tf.points[2].value).toBeGreaterThan(0.95);
    const iso = defaultRendererParams('iso', tf).surfaces as { value: number }[];
    expect(iso[0].value).toBeGreaterThan(tf.points[0].value);
    expect(iso[0].value).toBeLessThan(tf.points[1].value);
  });
});
