import { describe, expect, it } from 'vitest';
import { preprocess } from '../src/index.js';

describe('preprocess', () => {
  const src = ['a', '#if X', 'x', '#elif Y == 2 && !Z', 'y', '#else', 'e', '#if Z', 'z', '#endif', '#endif', 'b'].join('\n');
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
});
