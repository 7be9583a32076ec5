// Every GLSL/WGSL twin (<name>.glsl.ts beside <name>.wgsl.ts, in any package) declares the same
// thing in both languages: the same exports, the same preprocessor flags in its #if/#elif lines
// (preprocess.ts, applied to both) and the same functions. Drift then fails here, in a unit
// test, and not only in a browser test on one backend.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const PACKAGES = fileURLToPath(new URL('../..', import.meta.url));

type Kind = 'export' | 'flag' | 'function';
/**
 * Differences that are meant, each with why. `only`: the language that has the name and the
 * other lacks. The test fails when one is no longer needed, so the list stays true.
 */
const EXCEPTIONS: { twin: string; kind: Kind; name: string; only: 'glsl' | 'wgsl'; reason: string }[] = [];

/** Every twin's path without the .glsl.ts / .wgsl.ts ending, relative to packages/, with whichever halves exist. */
function findTwins(): { stem: string; glsl: boolean; wgsl: boolean }[] {
  const stems = new Map<string, { glsl: boolean; wgsl: boolean }>();
  for (const pkg of fs.readdirSync(PACKAGES)) {
    const src = path.join(PACKAGES, pkg, 'src');
    if (!fs.existsSync(src)) continue;
    for (const file of fs.readdirSync(src, { recursive: true }).map(String)) {
      const m = /^(.*)\.(glsl|wgsl)\.ts$/.exec(file);
      if (!m) continue;
      const stem = path.posix.join(pkg, 'src', m[1].split(path.sep).join('/'));
      const entry = stems.get(stem) ?? { glsl: false, wgsl: false };
      entry[m[2] as 'glsl' | 'wgsl'] = true;
      stems.set(stem, entry);
    }
  }
  return [...stems].map(([stem, halves]) => ({ stem, ...halves })).sort((a, b) => a.stem.localeCompare(b.stem));
}

/** The names in a shader's #if / #elif conditions (preprocess.ts's syntax: NAME, !NAME, NAME OP INTEGER). */
function flagNames(source: string): Set<string> {
  const names = new Set<string>();
  for (const m of source.matchAll(/^\s*#(?:if|elif)\b(.*)$/gm))
    for (const n of m[1].matchAll(/[A-Za-z_][A-Za-z0-9_]*/g)) names.add(n[0]);
  return names;
}

const GLSL_KEYWORDS = new Set(['if', 'for', 'while', 'switch', 'return', 'else']);

/**
 * Function definitions: GLSL `type name(…) {` (not prototypes or calls), WGSL `fn name(`. A
 * kernel's entry point is GLSL's `main` and WGSL's `@fragment fn fs_main` (the backends' rule),
 * counted as one name.
 */
function functionNames(source: string, lang: 'glsl' | 'wgsl'): Set<string> {
  const names = new Set<string>();
  if (lang === 'wgsl')
    for (const m of source.matchAll(/\bfn\s+([A-Za-z_][A-Za-z0-9_]*)\s*\(/g))
      names.add(m[1] === 'fs_main' ? 'main' : m[1]);
  else
    for (const m of source.matchAll(/\b([A-Za-z_][A-Za-z0-9_]*)\s+([A-Za-z_][A-Za-z0-9_]*)\s*\([^()]*\)\s*\{/g))
      if (!GLSL_KEYWORDS.has(m[1]) && !GLSL_KEYWORDS.has(m[2])) names.add(m[2]);
  return names;
}

/** The shader text of a module: its string exports, joined. */
function shaderText(mod: Record<string, unknown>): string {
  return Object.values(mod)
    .filter((v): v is string => typeof v === 'string')
    .join('\n');
}

const TWINS = findTwins();
type Lang = 'glsl' | 'wgsl';
/** What each complete twin declares, per language. */
const DECLARED = await Promise.all(
  TWINS.filter((t) => t.glsl && t.wgsl).map(async ({ stem }) => {
    const read = async (lang: Lang) => {
      const mod = (await import(/* @vite-ignore */ path.join(PACKAGES, `${stem}.${lang}.ts`))) as Record<
        string,
        unknown
      >;
      const text = shaderText(mod);
      return {
        mod,
        names: { export: new Set(Object.keys(mod)), flag: flagNames(text), function: functionNames(text, lang) },
      };
    };
    return { stem, glsl: await read('glsl'), wgsl: await read('wgsl') };
  }),
);

/** The names of `kind` that `lang` declares and its twin does not, less the listed exceptions. */
function unexplained(twin: (typeof DECLARED)[number], kind: Kind, lang: Lang): string[] {
  const other = lang === 'glsl' ? twin.wgsl : twin.glsl;
  return [...twin[lang].names[kind]].filter(
    (name) =>
      !other.names[kind].has(name) &&
      !EXCEPTIONS.some((e) => e.twin === twin.stem && e.kind === kind && e.name === name && e.only === lang),
  );
}

describe('GLSL/WGSL twins', () => {
  it('are found in every package that has shaders, and every half has its twin', () => {
    expect(TWINS.length).toBeGreaterThan(10);
    // core, post and every renderer package (each has kernels).
    const withShaders = ['core', 'post', ...fs.readdirSync(PACKAGES).filter((p) => p.startsWith('renderer-'))];
    for (const pkg of withShaders)
      expect(
        TWINS.some((t) => t.stem.startsWith(`${pkg}/`)),
        pkg,
      ).toBe(true);
    expect(TWINS.filter((t) => !t.glsl || !t.wgsl).map((t) => t.stem)).toEqual([]);
  });

  it('reads function definitions and #if flags the way the twins write them', () => {
    const glsl = `float g(float a);\nvec3 shade(vec3 p,\n  float t) {\n  if (t > 0.0) { return p; } else if (t < 0.0) {}\n  float x = g(t);\n}\nvoid main() {}`;
    expect([...functionNames(glsl, 'glsl')].sort()).toEqual(['main', 'shade']);
    const wgsl = 'fn shade(p: vec3f, t: f32) -> vec3f { let x = g(t); return p; }\n@fragment fn fs_main() {}';
    expect([...functionNames(wgsl, 'wgsl')].sort()).toEqual(['main', 'shade']);
    expect([...flagNames('#if A && !B\nx\n  #elif C >= 2 || D\n#else\n#endif')].sort()).toEqual(['A', 'B', 'C', 'D']);
  });

  it('declare something to compare: functions and flags are found', () => {
    const total = (kind: Kind) => DECLARED.reduce((n, t) => n + t.glsl.names[kind].size, 0);
    expect(total('function')).toBeGreaterThan(30);
    expect(total('flag')).toBeGreaterThan(3);
  });

  for (const twin of DECLARED) {
    describe(twin.stem, () => {
      it('exports the same names, of the same kinds (non-strings equal)', () => {
        expect(unexplained(twin, 'export', 'glsl'), 'only in GLSL').toEqual([]);
        expect(unexplained(twin, 'export', 'wgsl'), 'only in WGSL').toEqual([]);
        const g = twin.glsl.mod,
          w = twin.wgsl.mod;
        for (const k of Object.keys(g).filter((k) => k in w)) {
          expect(typeof w[k], k).toBe(typeof g[k]);
          if (typeof g[k] !== 'string' && typeof g[k] !== 'function') expect(w[k], k).toEqual(g[k]);
        }
      });

      it('tests the same #if / #elif flags', () => {
        expect(unexplained(twin, 'flag', 'glsl'), 'only in GLSL').toEqual([]);
        expect(unexplained(twin, 'flag', 'wgsl'), 'only in WGSL').toEqual([]);
      });

      it('defines the same functions', () => {
        expect(unexplained(twin, 'function', 'glsl'), 'only in GLSL').toEqual([]);
        expect(unexplained(twin, 'function', 'wgsl'), 'only in WGSL').toEqual([]);
      });
    });
  }

  it('need every exception listed (a stale one is removed)', () => {
    const stale = EXCEPTIONS.filter((e) => {
      const twin = DECLARED.find((t) => t.stem === e.twin);
      const other = e.only === 'glsl' ? twin?.wgsl : twin?.glsl;
      return !twin || !twin[e.only].names[e.kind].has(e.name) || other!.names[e.kind].has(e.name);
    });
    expect(stale).toEqual([]);
  });
});
