import { describe, expect, it } from 'vitest';
import { UniformLayout } from '../src/uniforms/layout.js';

// Offsets below were worked out by hand from the std140 rules (GLSL ES 3.0 §2.12.6.4)
// and WGSL's uniform address-space layout rules (WGSL §13.4.1), not read off the code.
describe('UniformLayout', () => {
  const layout = new UniformLayout('Params', [
    { name: 'a', type: 'f32' }, //        0
    { name: 'position', type: 'vec3' }, // align 16 → 16..28
    { name: 'b', type: 'f32' }, //        packs into vec3's tail → 28
    { name: 'view', type: 'mat4' }, //    align 16 → 32..96
    { name: 'c', type: 'vec2' }, //       96..104
    { name: 'd', type: 'vec3' }, //       align 16 → 112..124
    { name: 'e', type: 'u32' }, //        124
    { name: 'lights', type: 'vec4', count: 3 }, // 128, stride 16 → 176
    { name: 'f', type: 'f32' }, //        176 → block size rounds to 192
  ]);

  it('derives the std140 / WGSL offsets', () => {
    const offsets = Object.fromEntries(layout.fields.map((f) => [f.name, f.offset]));
    expect(offsets).toEqual({ a: 0, position: 16, b: 28, view: 32, c: 96, d: 112, e: 124, lights: 128, f: 176 });
    expect(layout.byteSize).toBe(192);
  });

  it('emits a GLSL std140 block and a WGSL struct with the same members in order', () => {
    expect(layout.glslBlock()).toBe(
      'layout(std140) uniform ParamsBlock {\n  float a;\n  vec3 position;\n  float b;\n  mat4 view;\n  vec2 c;\n  vec3 d;\n  uint e;\n  vec4 lights[3];\n  float f;\n} u;\n',
    );
    expect(layout.wgslStruct()).toBe(
      'struct Params {\n  a: f32,\n  position: vec3f,\n  b: f32,\n  view: mat4x4f,\n  c: vec2f,\n  d: vec3f,\n  e: u32,\n  lights: array<vec4f, 3>,\n  f: f32,\n};\n',
    );
  });

  it('packs values at their offsets, integers as integers', () => {
    const mat = Array.from({ length: 16 }, (_, i) => i + 1);
    const buf = layout.pack({
      a: 1.5,
      position: [2, 3, 4],
      b: 5,
      view: mat,
      e: 0xffffffff,
      lights: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12],
      f: -1,
    });
    const f32 = new Float32Array(buf);
    const u32 = new Uint32Array(buf);
    expect(f32[0]).toBe(1.5);
    expect([f32[4], f32[5], f32[6], f32[7]]).toEqual([2, 3, 4, 5]);
    expect(Array.from(f32.subarray(8, 24))).toEqual(mat);
    expect(u32[31]).toBe(0xffffffff);
    expect(Array.from(f32.subarray(32, 44))).toEqual([1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]);
    expect(f32[44]).toBe(-1);
    expect(buf.byteLength).toBe(192);
  });

  it('rejects wrong arity, unknown names and scalar arrays', () => {
    expect(() => layout.pack({ position: [1, 2] })).toThrow(/takes 3 numbers/);
    expect(() => layout.pack({ nope: 1 })).toThrow(/not in Params/);
    expect(() => new UniformLayout('X', [{ name: 'w', type: 'f32', count: 4 }])).toThrow(/vec4, ivec4, uvec4 or mat4/);
    expect(
      () =>
        new UniformLayout('X', [
          { name: 'a', type: 'f32' },
          { name: 'a', type: 'f32' },
        ]),
    ).toThrow(/duplicate/);
  });
});
