export { VptError, isVptError, type VptErrorCode } from './errors.js';

export * from './scene/volume.js';
export * from './scene/camera.js';
export * from './scene/lights.js';
export * from './scene/transfer-function.js';
export * from './scene/transfer-function-json.js';
export * from './scene/transfer-function-presets.js';
export * from './scene/scene.js';
export * from './scene/procedural.js';

export { UniformLayout, type UniformField, type UniformType, type UniformValues, type UniformValue, type FieldPlacement } from './uniforms/layout.js';

export type * from './gpu/backend.js';
export { createBackend } from './gpu/create-backend.js';
export { createWebGL2Backend } from './gpu/webgl2/webgl2-backend.js';
export { createWebGPUBackend, isWebGPUAvailable } from './gpu/webgpu/webgpu-backend.js';

export type { Renderer, KernelSource, AuxiliaryTexture, AuxiliaryPass } from './renderer.js';
export { BaseRenderer } from './base-renderer.js';
export { RUNNING_MEAN_INTEGRATE, COPY_ACCUMULATION_RENDER } from './shaders/accumulation-kernels.js';
export type { PostStep } from './post-step.js';
export { RenderContext, type RenderContextOptions, type RenderStats } from './context/render-context.js';

export { SCENE_UNIFORM_FIELDS, sceneUniformValues } from './shaders/scene-uniforms.js';
export { GLSL_RNG, GLSL_RAY, GLSL_VOLUME, GLSL_COMMON } from './shaders/glsl-common.js';
export { WGSL_RNG, WGSL_RAY, WGSL_VOLUME, WGSL_COMMON } from './shaders/wgsl-common.js';
export { glslCommon, GLSL_GRADIENT, GLSL_TRANSFER_2D, type CommonChunkOptions } from './shaders/glsl-common.js';
export { wgslCommon, WGSL_GRADIENT, WGSL_TRANSFER_2D } from './shaders/wgsl-common.js';
export { gradientAtlasLayout, atlasTexel, GLSL_ATLAS, WGSL_ATLAS, type GradientAtlasLayout } from './gradient/atlas.js';
export { gradientMagnitudes, maxGradientMagnitude } from './gradient/gradient-cpu.js';
export { buildGradientVolume, destroyGradientVolume, type GradientVolume } from './gradient/gradient-volume.js';
export { GLSL_SAMPLING, GLSL_ENVIRONMENT_MAP } from './shaders/glsl-sampling.js';
export { WGSL_SAMPLING, WGSL_ENVIRONMENT_MAP } from './shaders/wgsl-sampling.js';
export * from './scene/environment-sampling.js';

export * as reference from './reference/cpu-reference.js';

export * from './validation/limits.js';
export { describeValue, checkNumber, checkNumbers, checkOneOf, checkBoolean, checkString, checkObject, checkKnownKeys, type NumberRule } from './validation/checks.js';
export { validateParams, validateStepParams, minStepSize, STEP_RULE, type ParamSpec, type ParamSpecs } from './validation/params.js';
export { validateSceneForDevice } from './validation/device.js';
