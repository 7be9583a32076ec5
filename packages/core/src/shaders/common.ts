import type { KernelSource } from '../renderer.js';
import * as glsl from './common.glsl.js';
import * as wgsl from './common.wgsl.js';
import { preprocess } from './preprocess.js';
import { labelSupport } from '../scene/label-support.js';

/** Options of the generate pass's shared chunks, derived from the scene by RenderContext. */
export interface CommonChunkOptions {
  /** The transfer function is 2D: transferAt() reads value x normalized gradient magnitude. */
  tf2d?: boolean;
  /** The gradient textures are bound: sampleGradientMagnitude() / normalizedGradientAt() exist. */
  gradient?: boolean;
  /** The volume texture is bound with `filter: 'linear'`: sample it with one filtered fetch (volume-format.ts). */
  hardwareFilter?: boolean;
  /** The volume is bricked (bricking/): `volume` is the brick atlas, read through `pageTable` and `brickLevels`. */
  bricked?: boolean;
  /** The scene clips (scene/clip.ts): clipRayInterval() / isClipped() exist, reading the clip uniforms. */
  clip?: boolean;
  /** A channel scene's drawn channels (1–4; scene/channels.ts): sampleChannels() and the mixture's transferAt(); 0 or absent: scalar. */
  channels?: number;
  /** The scene has a label volume its renderer draws (scene/labels.ts): labelIdAt() / labelAt() and the image + labels transferAt() exist. */
  labels?: boolean;
  /** The scene has a slice plane its renderer draws (scene/slice-plane.ts): slicePlaneHit() / slicePlaneColor() exist. */
  slicePlane?: boolean;
  /** The slice plane reads the voxel holding the point (else the shared trilinear filter). */
  slicePlaneNearest?: boolean;
  /** The slice plane's colour comes from the `slicePlaneColormap` texture (else grey). */
  slicePlaneTable?: boolean;
}

/**
 * The shared chunks for a generate pass in both languages: RNG, rays, volume sampling (exact
 * or hardware-filtered), the gradient helpers when bound and the matching transferAt(). A scene with a 1D transfer
 * function whose renderer needs no gradient compiles no gradient code (docs/design.md,
 * "Leave out what a scene does not need").
 */
export function commonChunks(opts: CommonChunkOptions = {}): KernelSource {
  const flags = {
    GRADIENT: !!(opts.gradient || opts.tf2d),
    TF_2D: !!opts.tf2d,
    HARDWARE_FILTER: !!opts.hardwareFilter,
    BRICKED: !!opts.bricked,
    CLIP: !!opts.clip,
    CHANNELS: opts.channels ?? 0,
    LABELS: !!opts.labels,
    SLICE_PLANE: !!opts.slicePlane,
    SLICE_PLANE_NEAREST: !!opts.slicePlaneNearest,
    SLICE_PLANE_TABLE: !!opts.slicePlaneTable,
  };
  // The label chunk is registered by enableLabels() (scene/label-support.ts), so bundles without labels do not carry it.
  const chunks = opts.labels ? labelSupport().chunks : null;
  return {
    glsl: preprocess(
      chunks ? glsl.GENERATE_CHUNKS.replace(glsl.LABELS_PLACEHOLDER, chunks.glsl) : glsl.GENERATE_CHUNKS,
      flags,
    ),
    wgsl: preprocess(
      chunks ? wgsl.GENERATE_CHUNKS.replace(wgsl.LABELS_PLACEHOLDER, chunks.wgsl) : wgsl.GENERATE_CHUNKS,
      flags,
    ),
  };
}

/** The integrate and render passes' shared chunks (texture-free RNG and rays). */
export const PASS_CHUNKS: KernelSource = { glsl: glsl.PASS_CHUNKS, wgsl: wgsl.PASS_CHUNKS };
