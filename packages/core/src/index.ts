export { VptError, isVptError, type VptErrorCode } from './errors.js';
export {
  fetchWithPolicy,
  resolveRequestPolicy,
  RequestError,
  DEFAULT_REQUEST_POLICY,
  type RequestPolicy,
  type RequestFailure,
  type FetchOptions,
  type FetchedBytes,
} from './io/request.js';

export * from './scene/volume.js';
export * from './scene/camera.js';
export * from './scene/lights.js';
export * from './scene/transfer-function.js';
export * from './scene/transfer-function-json.js';
export * from './scene/transfer-function-presets.js';
export * from './scene/scene.js';
export * from './scene/clip.js';
export * from './scene/channels.js';
// Label volumes are opt-in: their code is the subpath @vpt/core/labels (scene/labels.ts: enableLabels()
// and the model's functions), kept out of this entry (the viewer's one-file bundle re-exports it whole).
export type { LabelEntry, SceneLabels } from './scene/labels.js';
export { labelSupport, registerLabelSupport, type LabelSupport } from './scene/label-support.js';
export * from './scene/colormaps.js';
export * from './scene/slice-geometry.js';
export * from './scene/slice-window.js';
export * from './scene/slice-plane.js';
export * from './scene/procedural.js';
export * from './scene/raw-sidecar.js';
export * from './scene/axis-codes.js';
export * from './scene/time-series.js';

export {
  UniformLayout,
  type UniformField,
  type UniformType,
  type UniformValues,
  type UniformValue,
  type FieldPlacement,
} from './uniforms/layout.js';

export type * from './gpu/backend.js';
export { isFilterable, sliceCount, BYTES_PER_TEXEL } from './gpu/backend.js';
export { floatToHalf, halfToFloat, toHalfArray, fromHalfArray } from './gpu/half-float.js';
export { createBackend } from './gpu/create-backend.js';
export { createWebGL2Backend } from './gpu/webgl2/webgl2-backend.js';
export { createWebGPUBackend, isWebGPUAvailable } from './gpu/webgpu/webgpu-backend.js';

export type { Renderer, KernelSource, AuxiliaryTexture, AuxiliaryPass, VolumeBinding } from './renderer.js';
export {
  planVolumeUpload,
  planChannelUpload,
  channelTextureData,
  channelComponents,
  uploadsDataAsIs,
  volumeTextureData,
  volumeTextureSlab,
  volumeValueMapping,
  type VolumeSampling,
  type VolumeUpload,
  type VolumeFormatOptions,
} from './gpu/volume-format.js';
export { downsampleVolume, fitFactors } from './scene/downsample.js';
export * from './bricking/index.js';
export { BaseRenderer } from './base-renderer.js';
export { RUNNING_MEAN_INTEGRATE, HALF_MEANS_INTEGRATE, COPY_ACCUMULATION_RENDER } from './shaders/accumulation.js';
export type { PostStep } from './post-step.js';
export { DEFAULT_GPU_BYTES, type RenderContextOptions } from './context/context-options.js';
export { RenderContext, type RenderStats, type GpuBytes, type DepthLimit } from './context/render-context.js';
export type { TemporalOptions } from './context/temporal-reuse.js';
export type { RenderWarning, BrickLoadWarning, VolumeDownsampledWarning } from './context/volume-fit.js';

export { CHANNEL_UNIFORM_FIELDS, SCENE_UNIFORM_FIELDS, sceneUniformValues } from './shaders/scene-uniforms.js';
// Shader chunks: each <name>.glsl.ts / <name>.wgsl.ts pair exports the same identifiers;
// the public names carry the language as a prefix.
export {
  RNG as GLSL_RNG,
  DEPTH_LIMIT as GLSL_DEPTH_LIMIT,
  RAY as GLSL_RAY,
  GRADIENT as GLSL_GRADIENT,
  TRANSFER_2D as GLSL_TRANSFER_2D,
} from './shaders/common.glsl.js';
export {
  RNG as WGSL_RNG,
  DEPTH_LIMIT as WGSL_DEPTH_LIMIT,
  RAY as WGSL_RAY,
  GRADIENT as WGSL_GRADIENT,
  TRANSFER_2D as WGSL_TRANSFER_2D,
} from './shaders/common.wgsl.js';
export { commonChunks, PASS_CHUNKS, type CommonChunkOptions } from './shaders/common.js';
// The sampling and environment-map chunks (ISO, MCRT) are the subpath @vpt/core/sampling (shaders/sampling.ts).
export { SLICE_ATLAS as GLSL_SLICE_ATLAS } from './shaders/slice-atlas.glsl.js';
export { SLICE_ATLAS as WGSL_SLICE_ATLAS } from './shaders/slice-atlas.wgsl.js';
export { sliceAtlasLayout, atlasTexel, type SliceAtlasLayout } from './shaders/slice-atlas.js';
export { environmentTextures, environmentTexturesKey, objectId } from './shaders/environment-textures.js';
export { preprocess, evalCondition, type Flags } from './shaders/preprocess.js';
export { gradientMagnitudes, maxGradientMagnitude } from './gradient/gradient-cpu.js';
export { buildGradientVolume, destroyGradientVolume, type GradientVolume } from './gradient/gradient-volume.js';
export * from './scene/environment-sampling.js';
export * from './majorant/majorant-grid.js';
export * as GLSL_MAJORANT_BUILD from './majorant/majorant-build.glsl.js';
export * as WGSL_MAJORANT_BUILD from './majorant/majorant-build.wgsl.js';
export * from './majorant/grid-textures.js';
export { CELL_WALK as GLSL_CELL_WALK } from './majorant/cell-walk.glsl.js';
export { CELL_WALK as WGSL_CELL_WALK } from './majorant/cell-walk.wgsl.js';

export * as reference from './reference/cpu-reference.js';

export {
  RENDERER_CATALOG,
  DEFAULT_RENDERER_NAME,
  rendererCatalogEntry,
  rendererNames,
  type RendererCatalogEntry,
} from './catalog/renderer-catalog.js';
export {
  defineRenderer,
  stepInVoxels,
  paramSpecsOf,
  validateRendererParams,
  resolveRendererParams,
  constantDefault,
  paramUniformFields,
  paramUniformValues,
  rendererControls,
  type RendererDescriptor,
  type RendererParam,
  type RendererParams,
  type RendererParamSpec,
  type ParamsOf,
  type ParamUi,
  type ParamUniform,
  type NumberParam,
  type StepParam,
  type EnumParam,
  type BooleanParam,
  type CustomParam,
  type RendererLookDefaults,
  type RendererInputs,
} from './catalog/renderer-descriptor.js';
export * from './validation/limits.js';
export {
  describeValue,
  checkNumber,
  countUpTo,
  LATLONG_SIDE_RULE,
  checkNumbers,
  checkOneOf,
  checkBoolean,
  checkString,
  checkObject,
  checkKnownKeys,
  type NumberRule,
} from './validation/checks.js';
export {
  validateParams,
  validateStepParams,
  minStepSize,
  STEP_RULE,
  type ParamSpec,
  type ParamSpecs,
} from './validation/params.js';
export { validateSceneForDevice } from './validation/device.js';
// The blue-noise sampler itself is the subpath @vpt/core/blue-noise (shaders/blue-noise.ts), imported by the
// renderers only, so the viewer's entry (core and the descriptors) does not carry it.
export { SAMPLER_PARAM, samplerParam, type Sampler } from './shaders/sampler-param.js';
