import { describe, expect, it } from 'vitest';
import { reference } from '../src/index.js';

describe('PCG hash (CPU twin of the kernels RNG)', () => {
  // Independent re-implementation with BigInt arithmetic modulo 2^32, following
  // Jarzynski & Olano 2020's listing; the kernel twin must match it exactly.
  const M = 0xffffffffn;
  function pcgBig(v: number): number {
    const state = (BigInt(v) * 747796405n + 2891336453n) & M;
    const word = (((state >> ((state >> 28n) + 4n)) ^ state) * 277803737n) & M;
    return Number(((word >> 22n) ^ word) & M);
  }
  it('matches a BigInt implementation over many inputs', () => {
    for (const v of [0, 1, 2, 0x7fffffff, 0x80000000, 0xffffffff, 123456789, 42]) expect(reference.pcgHash(v)).toBe(pcgBig(v));
    for (let i = 0; i < 2000; i++) {
      const v = (i * 2654435761) >>> 0;
      expect(reference.pcgHash(v)).toBe(pcgBig(v));
    }
  });
  it('streams uniform numbers in [0, 1) with the right mean', () => {
    let sum = 0;
    const n = 20000;
    for (let i = 0; i < n; i++) {
      const x = new reference.CpuRng(i % 97, Math.floor(i / 97), 3, 7).next();
      expect(x).toBeGreaterThanOrEqual(0);
      expect(x).toBeLessThan(1);
      sum += x;
    }
    expect(Math.abs(sum / n - 0.5)).toBeLessThan(4 * Math.sqrt(1 / 12 / n));
  });
});
