/**
 * WGSL source generation for vpt passes: the prelude that backend.ts documents (the
 * uniform struct at group 0 binding 0, textures at bindings 1 + k, the backend-owned
 * VptBuiltins at group 1, the VptOut MRT struct, vptPixel()/vptTargetSize(), define
 * constants) and the buffer-less full-screen vertex shader.
 */
import type { PassDescriptor } from '../backend.js';

/** Entry points the backend uses; the kernel defines fs_main, the backend owns the vertex stage. */
export const FRAGMENT_ENTRY = 'fs_main';
export const VERTEX_ENTRY = 'vpt_vs_main';

/** Byte size of `struct VptBuiltins { targetSize: vec2i, flipY: i32, pad: i32 }`. */
export const BUILTINS_BYTE_SIZE = 16;

/**
 * One triangle that covers clip space, built from vertex_index so no vertex buffer is
 * needed: indices 0, 1, 2 give (-1,-1), (3,-1), (-1,3). Its own module, so kernel names
 * cannot clash with it and compiler line numbers match the fragment source.
 */
export const FULLSCREEN_VERTEX_WGSL = /* wgsl */ `
@vertex fn ${VERTEX_ENTRY}(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
  let p = vec2f(f32((i & 1u) << 2u) - 1.0, f32((i & 2u) << 1u) - 1.0);
  return vec4f(p, 0.0, 1.0);
}
`;

const IDENT = /^[A-Za-z_][A-Za-z0-9_]*$/;
const I32_MIN = -2147483648;
const I32_MAX = 2147483647;

/** A define's WGSL declaration: `const NAME: bool = true;`, `: i32 = 3;` for integers, `: f32 = 0.5;` otherwise. */
export function wgslDefine(name: string, value: boolean | number): string {
  if (!IDENT.test(name)) throw new RangeError(`bad define name "${name}"`);
  if (typeof value === 'boolean') return `const ${name}: bool = ${value};\n`;
  if (!Number.isFinite(value)) throw new RangeError(`define "${name}" must be a finite number, got ${value}`);
  if (Number.isInteger(value)) {
    if (value < I32_MIN || value > I32_MAX) throw new RangeError(`define "${name}" = ${value} does not fit an i32`);
    return `const ${name}: i32 = ${Object.is(value, -0) ? 0 : value};\n`;
  }
  // A non-integer's shortest decimal form ("0.5", "1e-7") is a valid WGSL float literal.
  return `const ${name}: f32 = ${String(value)};\n`;
}

/** Define constants sorted by name, so equal define sets give equal sources (and cache keys). */
export function wgslDefines(defines: PassDescriptor['defines']): string {
  if (!defines) return '';
  return Object.keys(defines)
    .sort()
    .map((name) => wgslDefine(name, defines[name]))
    .join('');
}

/** A pass with a `filter: 'linear'` binding gets the clamp-to-edge linear sampler `vptLinearSampler`. */
export function usesLinearSampler(desc: PassDescriptor): boolean {
  return desc.textures.some((t) => t.filter === 'linear');
}

/** The sampler's binding: right after the textures (1 + texture count). */
export function linearSamplerBinding(desc: PassDescriptor): number {
  return 1 + desc.textures.length;
}

/** The full fragment module: prelude followed by the kernel's source. */
export function buildWgslSource(desc: PassDescriptor): string {
  const parts: string[] = [wgslDefines(desc.defines)];
  // WGSL forbids empty structs; a layout without fields has nothing to read, so `u` is left
  // out of the shader (the explicit bind group layout still holds binding 0).
  if (desc.uniforms.fields.length > 0) {
    parts.push(desc.uniforms.wgslStruct());
    parts.push(`@group(0) @binding(0) var<uniform> u: ${desc.uniforms.structName};\n`);
  }
  desc.textures.forEach((t, k) => {
    if (!IDENT.test(t.name)) throw new RangeError(`bad texture name "${t.name}" in pass "${desc.label}"`);
    parts.push(
      `@group(0) @binding(${1 + k}) var ${t.name}: ${t.dimension === '3d' ? 'texture_3d<f32>' : 'texture_2d<f32>'};\n`,
    );
  });
  if (usesLinearSampler(desc))
    parts.push(`@group(0) @binding(${linearSamplerBinding(desc)}) var vptLinearSampler: sampler;\n`);
  parts.push('struct VptBuiltins { targetSize: vec2i, flipY: i32, pad: i32 };\n');
  parts.push('@group(1) @binding(0) var<uniform> vpt: VptBuiltins;\n');
  if (desc.outputs.length === 0) throw new RangeError(`pass "${desc.label}" has no outputs`);
  parts.push(`struct VptOut {\n${desc.outputs.map((_, k) => `  @location(${k}) out${k}: vec4f,\n`).join('')}};\n`);
  parts.push(`// Pixel (column, row from the top): WebGPU's framebuffer origin is the top-left corner,
// for offscreen targets and the canvas alike, so the fragment position is used as is.
fn vptPixel(fragCoord: vec4f) -> vec2i { return vec2i(fragCoord.xy); }
fn vptTargetSize() -> vec2i { return vpt.targetSize; }
`);
  parts.push(desc.wgsl);
  return parts.join('');
}
