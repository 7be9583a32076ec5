import { describe, expect, it } from 'vitest';
import { UniformLayout, isVptError, type GpuTexture, type PassDescriptor } from '../src/index.js';
import {
  checkBoundTexture,
  checkCanvasOutputs,
  checkCanvasSize,
  checkPassOutputs,
  checkTargetOutputs,
  checkTextureCapabilities,
  checkTextureSize,
  checkUniformBytes,
  givenTexture,
  textureLabelAndDepth,
} from '../src/gpu/validation.js';

const layout = new UniformLayout('P', [{ name: 'a', type: 'vec4' }]);
const pass = (outputs: PassDescriptor['outputs']): PassDescriptor => ({
  label: 'p',
  glsl: '',
  wgsl: '',
  uniforms: layout,
  textures: [{ name: 'src', dimension: '2d' }],
  outputs,
});
const tex = (format: GpuTexture['format'], dimension: '2d' | '3d' = '2d'): GpuTexture => ({
  dimension,
  width: 2,
  height: 2,
  depth: 1,
  format,
  label: `${format} tex`,
});
const limits = { max2D: 16, max3D: 8, name2D: 'MAX2D', name3D: 'MAX3D' };

describe('backend validation shared by WebGL 2 and WebGPU', () => {
  it('16-bit normalized and filtered float32 textures need their capabilities', () => {
    const names = { norm16: 'NORM16', float32Filterable: 'F32LINEAR' };
    const none = { norm16: false, float32Filterable: false },
      all = { norm16: true, float32Filterable: true };
    const d = (format: GpuTexture['format'], filter?: 'linear') => ({
      dimension: '3d' as const,
      width: 2,
      height: 2,
      depth: 2,
      format,
      ...(filter ? { filter } : {}),
    });
    expect(() => checkTextureCapabilities('v', d('r16unorm'), none, names)).toThrow(/needs NORM16/);
    expect(() => checkTextureCapabilities('v', d('r16snorm', 'linear'), all, names)).not.toThrow();
    expect(() => checkTextureCapabilities('v', d('r32float', 'linear'), none, names)).toThrow(
      /cannot be filtered here: that needs F32LINEAR/,
    );
    expect(() => checkTextureCapabilities('v', d('r32float'), none, names)).not.toThrow();
    expect(() => checkTextureCapabilities('v', d('r8unorm', 'linear'), none, names)).not.toThrow();
    try {
      checkTextureCapabilities('v', d('r16unorm'), none, names);
    } catch (e) {
      expect(isVptError(e) && e.code).toBe('missing-extension');
    }
  });

  it('a canvas draw has exactly one rgba8unorm output', () => {
    expect(() => checkCanvasOutputs(pass(['rgba8unorm']))).not.toThrow();
    expect(() => checkCanvasOutputs(pass(['rgba32float']))).toThrow(/one rgba8unorm output, not \[rgba32float\]/);
    expect(() => checkCanvasOutputs(pass(['rgba8unorm', 'rgba8unorm']))).toThrow(RangeError);
    expect(() => checkPassOutputs(pass([]))).toThrow(/has no outputs/);
  });

  it('a render target holds the formats the pass writes, in order', () => {
    expect(() =>
      checkTargetOutputs(pass(['r32float', 'rgba32float']), {
        label: 't',
        textures: [tex('r32float'), tex('rgba32float')],
      }),
    ).not.toThrow();
    expect(() =>
      checkTargetOutputs(pass(['r32float', 'rgba32float']), {
        label: 't',
        textures: [tex('rgba32float'), tex('r32float')],
      }),
    ).toThrow(/writes \[r32float, rgba32float\] but render target "t" holds \[rgba32float, r32float\]/);
  });

  it('draws bind every texture, of the right dimension, never one they write', () => {
    const p = pass(['rgba32float']);
    expect(() =>
      givenTexture(p, p.textures[0], { uniforms: new ArrayBuffer(16), textures: {}, target: 'canvas' }),
    ).toThrow(/needs texture "src"/);
    const written = tex('rgba32float');
    expect(() => checkBoundTexture(p, p.textures[0], written, [written])).toThrow(/feedback loop/);
    expect(() => checkBoundTexture(p, p.textures[0], tex('r32float', '3d'), [])).toThrow(
      /"src" is a 2d texture, got 3d/,
    );
    expect(() => checkUniformBytes(p, { uniforms: new ArrayBuffer(8), textures: {}, target: 'canvas' })).toThrow(
      /has 8 bytes, the layout needs 16/,
    );
  });

  it('texture sizes are positive integers within the named device limit', () => {
    expect(() => checkTextureSize('x', '2d', 16, 16, 1, limits)).not.toThrow();
    expect(() => checkTextureSize('x', '2d', 1.5, 1, 1, limits)).toThrow(/width must be a positive integer/);
    let e: unknown;
    try {
      checkTextureSize('x', '3d', 9, 1, 1, limits);
    } catch (err) {
      e = err;
    }
    expect(isVptError(e) && e.code === 'limit-exceeded' && /MAX3D is 8/.test(e.message)).toBe(true);
    expect(() => textureLabelAndDepth({ dimension: '2d', width: 1, height: 1, depth: 2, format: 'r32float' })).toThrow(
      /a 2D texture has depth 1/,
    );
    expect(textureLabelAndDepth({ dimension: '3d', width: 1, height: 1, depth: 4, format: 'r32float' })).toEqual({
      label: '3d r32float texture',
      depth: 4,
    });
    expect(() => checkCanvasSize(0, 4)).toThrow(/positive integers/);
  });
});
