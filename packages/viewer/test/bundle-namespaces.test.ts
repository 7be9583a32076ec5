/**
 * The one-file bundle's `core` and `post` are the packages less their CPU reference twins
 * (src/bundle-core.ts, src/bundle-post.ts): every other export is there and is the package's own.
 */
import * as core from '@vpt/core';
import * as post from '@vpt/post';
import { describe, expect, it } from 'vitest';
import * as bundleCore from '../src/bundle-core.js';
import * as bundlePost from '../src/bundle-post.js';

function check(pkg: Record<string, unknown>, bundled: Record<string, unknown>, dropped: string[]) {
  for (const name of dropped) {
    expect(pkg[name], `${name} exists in the package`).toBeDefined();
    expect(bundled[name], `${name} is left out of the bundle`).toBeUndefined();
  }
  const kept = Object.keys(pkg).filter((k) => !dropped.includes(k));
  for (const name of kept) expect(bundled[name], name).toBe(pkg[name]);
}

describe("the bundle's core and post namespaces", () => {
  it('core: everything but the CPU reference renderers', () => {
    check(core, bundleCore, ['reference']);
  });
  it("post: everything but the steps' CPU twins", () => {
    const refs = Object.keys(post).filter((k) => /Ref$/.test(k));
    expect(refs).toContain('denoiseRef');
    check(post, bundlePost, refs);
    // Every *Ref the package exports is shadowed (a new one must be added to bundle-post.ts).
    expect(
      Object.keys(bundlePost)
        .filter((k) => /Ref$/.test(k))
        .sort(),
    ).toEqual(refs.sort());
  });
});
