import { describe, expect, it } from 'vitest';
import { reference, type Camera, type Scene } from '@vpt/core';
import { axisPoint, draggedPosition, projectPoint } from '../src/clip-handles.js';

const CAMERA: Camera = { position: [-1.6, -0.35, 0.55], target: [0, 0, 0], up: [0, -1, 0], fovy: 0.75 };

describe('clip plane handles on the image', () => {
  it("project a point where the kernels' camera ray through that image point passes", () => {
    const aspect = 1.5;
    for (const p of [
      [0, 0, 0],
      [0.2, -0.1, 0.3],
      [-0.4, 0.25, -0.1],
    ]) {
      const s = projectPoint(CAMERA, aspect, p)!;
      const ray = reference.cameraRay({ camera: CAMERA } as Scene, 300, 200, s.x, s.y);
      const v = p.map((x, i) => x - ray.origin[i]);
      const t = v[0] * ray.dir[0] + v[1] * ray.dir[1] + v[2] * ray.dir[2];
      for (let i = 0; i < 3; i++) expect(ray.origin[i] + t * ray.dir[i]).toBeCloseTo(p[i], 9);
    }
    const centre = projectPoint(CAMERA, 1, [0, 0, 0])!;
    expect(centre.x).toBeCloseTo(0.5, 12);
    expect(centre.y).toBeCloseTo(0.5, 12);
    expect(projectPoint(CAMERA, 1, [-3, 0, 0])).toBeNull(); // behind the camera
  });

  it('a drag along the axis on screen moves the plane by that many world units; across it, not at all', () => {
    const range = { min: -0.5, max: 0.5 };
    const a = projectPoint(CAMERA, 1, axisPoint('z', 0))!;
    const b = projectPoint(CAMERA, 1, axisPoint('z', 0.1))!;
    const along = { dx: b.x - a.x, dy: b.y - a.y };
    expect(draggedPosition(CAMERA, 1, 'z', 0, along, range)).toBeCloseTo(0.1, 2);
    expect(draggedPosition(CAMERA, 1, 'z', 0, { dx: -along.dx, dy: -along.dy }, range)).toBeCloseTo(-0.1, 2);
    expect(draggedPosition(CAMERA, 1, 'z', 0, { dx: -along.dy, dy: along.dx }, range)).toBeCloseTo(0, 6);
    expect(draggedPosition(CAMERA, 1, 'z', 0.45, { dx: 10 * along.dx, dy: 10 * along.dy }, range)).toBe(0.5);
    // An axis pointing at the camera has no on-screen direction: the plane stays.
    const head: Camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };
    expect(draggedPosition(head, 1, 'z', 0.1, { dx: 0.2, dy: 0.1 }, range)).toBe(0.1);
  });
});
