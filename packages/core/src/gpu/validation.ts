/**
 * The checks both backends make before they touch the GPU, in one place so the two agree
 * (what a draw may target, what a texture or render target may be, what a draw must bind).
 * Each throws a RangeError (a programming error of the caller) or a VptError
 * ('limit-exceeded') naming the device limit; the backends add only what is theirs
 * (ownership of objects, loss generations, device-specific limits).
 */
import { VptError } from '../errors.js';
import type {
  BackendCapabilities,
  DrawCall,
  GpuTexture,
  PassDescriptor,
  PassTextureBinding,
  TextureDescriptor,
  TextureFormat,
} from './backend.js';
import { isFilterable } from './backend.js';

/** The device's texture size limits, with the names each API gives them (for messages). */
export interface TextureSizeLimits {
  max2D: number;
  max3D: number;
  name2D: string;
  name3D: string;
}

/** A texture descriptor's label (a default one naming dimension and format) and depth (1 for 2D); rejects a 2D depth other than 1. */
export function textureLabelAndDepth(desc: TextureDescriptor): { label: string; depth: number } {
  const label = desc.label ?? `${desc.dimension} ${desc.format} texture`;
  const depth = desc.dimension === '3d' ? (desc.depth ?? 1) : 1;
  if (desc.dimension === '2d' && desc.depth !== undefined && desc.depth !== 1) {
    throw new RangeError(`texture "${label}": a 2D texture has depth 1, got ${desc.depth}`);
  }
  return { label, depth };
}

/** Positive integer sizes within the device's limits (checked before the API would only report a validation error later). */
export function checkTextureSize(
  label: string,
  dimension: '2d' | '3d',
  width: number,
  height: number,
  depth: number,
  limits: TextureSizeLimits,
): void {
  for (const [name, v] of [
    ['width', width],
    ['height', height],
    ['depth', depth],
  ] as const) {
    if (!Number.isInteger(v) || v < 1)
      throw new RangeError(`texture "${label}": ${name} must be a positive integer, got ${v}`);
  }
  if (dimension === '3d') {
    if (width > limits.max3D || height > limits.max3D || depth > limits.max3D) {
      throw new VptError(
        'limit-exceeded',
        `3D texture "${label}" is ${width}x${height}x${depth}, but this device's ${limits.name3D} is ${limits.max3D}`,
      );
    }
  } else if (width > limits.max2D || height > limits.max2D) {
    throw new VptError(
      'limit-exceeded',
      `2D texture "${label}" is ${width}x${height}, but this device's ${limits.name2D} is ${limits.max2D}`,
    );
  }
}

/** What each backend names as the requirement of an optional capability (for messages). */
export interface CapabilityNames {
  norm16: string;
  float32Filterable: string;
}

/**
 * The optional capabilities a texture needs are present: the 16-bit unorm/snorm formats need norm16, a
 * `filter: 'linear'` float32 texture needs float32Filterable (VptError('missing-extension')).
 */
export function checkTextureCapabilities(
  label: string,
  desc: TextureDescriptor,
  caps: BackendCapabilities,
  names: CapabilityNames,
): void {
  if (/^(r|rg|rgba)16(unorm|snorm)$/.test(desc.format) && !caps.norm16) {
    throw new VptError('missing-extension', `texture "${label}" is ${desc.format}, which needs ${names.norm16}`);
  }
  if (desc.filter === 'linear' && !isFilterable(desc.format, caps)) {
    throw new VptError(
      'missing-extension',
      `texture "${label}" (${desc.format}) cannot be filtered here: that needs ${names.float32Filterable}`,
    );
  }
}

/** A render target has at least one colour attachment. */
export function checkTargetFormats(label: string, formats: readonly TextureFormat[]): void {
  if (formats.length === 0) throw new RangeError(`render target "${label}" needs at least one format`);
}

/** A pass writes at least one output. */
export function checkPassOutputs(desc: PassDescriptor): void {
  if (desc.outputs.length === 0) throw new RangeError(`pass "${desc.label}" has no outputs`);
}

/** The canvas is LDR: a pass that draws to it has exactly one rgba8unorm output, on both backends. */
export function checkCanvasOutputs(desc: PassDescriptor): void {
  if (desc.outputs.length !== 1 || desc.outputs[0] !== 'rgba8unorm') {
    throw new RangeError(
      `pass "${desc.label}" draws to the canvas, so it must have one rgba8unorm output, not [${desc.outputs.join(', ')}]`,
    );
  }
}

/** A render target holds exactly the formats the pass writes, in order. */
export function checkTargetOutputs(
  desc: PassDescriptor,
  target: { label: string; textures: readonly GpuTexture[] },
): void {
  if (
    target.textures.length !== desc.outputs.length ||
    target.textures.some((tex, k) => tex.format !== desc.outputs[k])
  ) {
    throw new RangeError(
      `pass "${desc.label}" writes [${desc.outputs.join(', ')}] but render target "${target.label}" holds [${target.textures.map((x) => x.format).join(', ')}]`,
    );
  }
}

/** The packed uniforms cover the pass's layout. */
export function checkUniformBytes(desc: PassDescriptor, call: DrawCall): void {
  if (call.uniforms.byteLength < desc.uniforms.byteSize) {
    throw new RangeError(
      `pass "${desc.label}": the uniform buffer has ${call.uniforms.byteLength} bytes, the layout needs ${desc.uniforms.byteSize}`,
    );
  }
}

/** The texture given for a binding: present (the caller checks ownership and returns its own object). */
export function givenTexture(desc: PassDescriptor, binding: PassTextureBinding, call: DrawCall): GpuTexture {
  const given = call.textures[binding.name];
  if (!given) throw new RangeError(`pass "${desc.label}" needs texture "${binding.name}"`);
  return given;
}

/** A bound texture has the binding's dimension and is not one the draw writes (no feedback loop). */
export function checkBoundTexture(
  desc: PassDescriptor,
  binding: PassTextureBinding,
  tex: GpuTexture,
  targetTextures: readonly GpuTexture[],
): void {
  if (tex.dimension !== binding.dimension) {
    throw new RangeError(
      `pass "${desc.label}": "${binding.name}" is a ${binding.dimension} texture, got ${tex.dimension} texture "${tex.label}"`,
    );
  }
  if (targetTextures.includes(tex)) {
    throw new RangeError(
      `pass "${desc.label}" reads texture "${tex.label}" while writing it (a feedback loop): ping-pong between two targets instead`,
    );
  }
}

/** Only 2D textures are read back. */
export function checkReadable(tex: GpuTexture): void {
  if (tex.dimension !== '2d') throw new RangeError(`readTexture reads 2D textures only; "${tex.label}" is 3D`);
}

/** A canvas size is two positive integers. */
export function checkCanvasSize(width: number, height: number): void {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    throw new RangeError(`canvas size must be positive integers, got ${width}x${height}`);
  }
}
