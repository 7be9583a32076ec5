/**
 * GLSL ES 3.0 source generation for vpt passes: the prelude that backend.ts documents
 * (precision, defines, the std140 uniform block, backend-owned uniforms, samplers,
 * MRT outputs, vptPixel()/vptTargetSize()) and the buffer-less full-screen vertex shader.
 */
import type { PassDescriptor } from '../backend.js';

/** Names of the backend-owned plain uniforms (set per draw, outside the user block). */
export const TARGET_SIZE_UNIFORM = 'vpt_targetSize';
export const FLIP_Y_UNIFORM = 'vpt_flipY';

/**
 * One triangle that covers clip space, built from gl_VertexID so no vertex buffer is
 * needed: ids 0, 1, 2 give (-1,-1), (3,-1), (-1,3).
 */
export const FULLSCREEN_VERTEX_SHADER = `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
`;

const IDENT = /^[A-Za-z_][A-Za-z0-9_]*$/;

/** Format a define's value as a GLSL literal: booleans 1/0, integers bare, other numbers with a decimal point. */
export function glslDefineValue(name: string, value: boolean | number): string {
  if (typeof value === 'boolean') return value ? '1' : '0';
  if (!Number.isFinite(value)) throw new RangeError(`define "${name}" must be a finite number, got ${value}`);
  if (Number.isInteger(value)) {
    // Plain digits: String() would switch to exponent form from 1e21 on, which is not an integer literal.
    return Math.abs(value) < 1e21 ? String(value) : value.toFixed(1);
  }
  const s = String(value);
  if (s.includes('.')) return s;
  // "1e-7" is a valid GLSL float, but the contract asks for a decimal point: "1.0e-7".
  const [mantissa, exponent] = s.split('e');
  return `${mantissa}.0e${exponent}`;
}

/** `#define NAME value` lines, sorted by name so equal define sets give equal sources (and cache keys). */
export function glslDefines(defines: PassDescriptor['defines']): string {
  if (!defines) return '';
  return Object.keys(defines)
    .sort()
    .map((name) => {
      if (!IDENT.test(name)) throw new RangeError(`bad define name "${name}"`);
      return `#define ${name} ${glslDefineValue(name, defines[name])}\n`;
    })
    .join('');
}

/** The full fragment shader: prelude followed by the kernel's source. */
export function buildFragmentSource(desc: PassDescriptor): string {
  const parts: string[] = [
    '#version 300 es\n',
    'precision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp sampler3D;\n',
    glslDefines(desc.defines),
  ];
  // An empty interface block is a GLSL syntax error; a layout without fields has nothing to read anyway.
  if (desc.uniforms.fields.length > 0) parts.push(desc.uniforms.glslBlock('u'));
  parts.push(`uniform highp ivec2 ${TARGET_SIZE_UNIFORM};\nuniform int ${FLIP_Y_UNIFORM};\n`);
  for (const t of desc.textures) {
    if (!IDENT.test(t.name)) throw new RangeError(`bad texture name "${t.name}" in pass "${desc.label}"`);
    parts.push(`uniform highp ${t.dimension === '3d' ? 'sampler3D' : 'sampler2D'} ${t.name};\n`);
  }
  desc.outputs.forEach((_, k) => parts.push(`layout(location = ${k}) out highp vec4 vpt_out${k};\n`));
  parts.push(`ivec2 vptTargetSize() { return ${TARGET_SIZE_UNIFORM}; }
// Pixel (column, row from the top). Offscreen targets store texel row 0 first, which is
// vpt's top row, so gl_FragCoord is used as is; the canvas shows GL row 0 at the bottom.
ivec2 vptPixel() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  return ${FLIP_Y_UNIFORM} != 0 ? ivec2(p.x, ${TARGET_SIZE_UNIFORM}.y - 1 - p.y) : p;
}
`);
  parts.push(desc.glsl);
  return parts.join('');
}
