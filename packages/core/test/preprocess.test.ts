import { describe, expect, it } from 'vitest';
import { commonChunks, preprocess } from '../src/index.js';

describe('preprocess', () => {
  const src = ['a', '#if X', 'x', '#elif Y == 2 && !Z', 'y', '#else', 'e', '#if Z', 'z', '#endif', '#endif', 'b'].join(
    '\n',
  );
  it('keeps the taken branch of nested #if/#elif/#else', () => {
    expect(preprocess(src, { X: true, Y: 2, Z: false })).toBe('a\nx\nb');
    expect(preprocess(src, { X: false, Y: 2, Z: false })).toBe('a\ny\nb');
    expect(preprocess(src, { X: false, Y: 1, Z: true })).toBe('a\ne\nz\nb');
    expect(preprocess(src, { X: false, Y: 2, Z: true })).toBe('a\ne\nz\nb');
    expect(preprocess('#if A || B > 3\nq\n#endif', { A: false, B: 4 })).toBe('q');
    expect(preprocess('#if A || B > 3\nq\n#endif', { A: false, B: 3 })).toBe('');
  });
  it('rejects unknown flags and unbalanced directives', () => {
    expect(() => preprocess('#if NOPE\n#endif', {})).toThrow(/unknown flag "NOPE"/);
    expect(() => preprocess('#if A\n', { A: true })).toThrow(/unterminated/);
    expect(() => preprocess('#endif', {})).toThrow(/without #if/);
  });
  it('keeps deferred #if blocks (with their #else) for a later run, inside resolved ones', () => {
    const src = [
      '#if A',
      'a',
      '#if G',
      'g',
      '#else',
      'ng',
      '#endif',
      '#else',
      'na',
      '#if G',
      'g2',
      '#endif',
      '#endif',
    ].join('\n');
    const first = preprocess(src, { A: true }, { defer: ['G'] });
    expect(first.split('\n')).toEqual(['a', '#if G', 'g', '#else', 'ng', '#endif']);
    expect(preprocess(first, { G: true })).toBe('a\ng');
    expect(preprocess(first, { G: false })).toBe('a\nng');
    expect(() => preprocess('#if G\n#elif A\n#endif', { A: true }, { defer: ['G'] })).toThrow(/deferred/);
  });
  it('picks the exact or hardware volume filter in the common chunks (one sampleVolumeTexel each)', () => {
    const exact = commonChunks({}),
      filtered = commonChunks({ hardwareFilter: true });
    for (const src of [exact.glsl, exact.wgsl, filtered.glsl, filtered.wgsl]) {
      expect(src.match(/(float|fn) sampleVolumeTexel/g)).toHaveLength(1);
      expect(src).toContain('volumeValue(sampleVolumeTexel(p))');
    }
    expect(exact.glsl).toContain('texelFetch(volume');
    expect(filtered.glsl).not.toContain('texelFetch(volume');
    expect(filtered.glsl).toContain('texture(volume');
    expect(exact.wgsl).not.toContain('vptLinearSampler');
    expect(filtered.wgsl).toContain('textureSampleLevel(volume, vptLinearSampler');
  });
});
