/**
 * The shape rules every scene description meets before its fields are checked: nesting at
 * most MAX_SCENE_DEPTH deep (a transfer function nested 5,000 levels deep overflowed the
 * stack of structuredClone and of the DevTools serializer, with no field named) and only
 * finite numbers (JSON has no Infinity: `1e999` parses as one, and it reaches the page as
 * null). Walked with an explicit stack, so the check itself cannot overflow.
 */
import { VptError } from '@vpt/core';

/** Deepest nesting of objects and arrays in a scene (a 2D transfer function's widget colour is 5 deep). */
export const MAX_SCENE_DEPTH = 32;

export function checkJsonShape(value: unknown, root = 'scene'): void {
  const stack: { v: unknown; path: string; depth: number }[] = [{ v: value, path: root, depth: 0 }];
  while (stack.length) {
    const { v, path, depth } = stack.pop()!;
    if (typeof v === 'number' && !Number.isFinite(v))
      throw new VptError(
        'invalid-scene',
        `${path}: ${v} is not a finite number (JSON has none; a literal like 1e999 overflows to Infinity); leave the field out for its default`,
      );
    if (typeof v !== 'object' || v === null) continue;
    if (depth >= MAX_SCENE_DEPTH)
      throw new VptError(
        'limit-exceeded',
        `${path}: nested deeper than ${MAX_SCENE_DEPTH} levels of objects and arrays (MAX_SCENE_DEPTH); no scene field needs that`,
      );
    if (Array.isArray(v)) {
      // Numbers are checked in place (a lat-long environment's data holds millions of them).
      for (let i = v.length - 1; i >= 0; i--) {
        const x: unknown = v[i];
        if (typeof x === 'number' ? !Number.isFinite(x) : typeof x === 'object' && x !== null)
          stack.push({ v: x, path: `${path}[${i}]`, depth: depth + 1 });
      }
    } else for (const [k, x] of Object.entries(v)) stack.push({ v: x, path: `${path}.${k}`, depth: depth + 1 });
  }
}
