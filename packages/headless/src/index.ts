export { launchChromium, chromiumExecutable, CHROMIUM_FLAGS, WEBGPU_FLAGS, type ChromiumOptions } from './chromium.js';
export { startStaticServer, mimeType, type StaticServer, type StaticServerOptions } from './server.js';
export {
  openVptPage,
  renderScene,
  PageError,
  type VptPageOptions,
  type VptPageSession,
  type RenderResult,
  type RenderSceneOptions,
  type PageRenderOptions,
} from './render.js';
export { encodePNG, decodePNG, opaque, encodePFM, decodePFM, type DecodedPFM } from './image-io.js';
export {
  readSceneFile,
  resolveSceneFiles,
  mountSceneFiles,
  checkSidecarFile,
  type SceneFileOptions,
} from './scene-files.js';
export { validateSceneDescription, RENDERER_PARAM_CHECKS, MAX_VOLUME_SIDE } from './validate-description.js';
export { requestPolicyFromEnv, REQUEST_POLICY_ENV } from './request-policy-env.js';
export { headlessPackageDir, findPackageDir, workspaceRoot, mountPagePackages, PAGE_PATH } from './packages.js';
export {
  SCENE_DEFAULTS,
  checkSceneDescription,
  selectTimeStep,
  type SceneDescription,
  type TimeSeriesVolumeDescription,
  type VolumeDescription,
  type RawVolumeDescription,
  type SidecarVolumeDescription,
  type ProceduralVolumeDescription,
  type EnvironmentDescription,
  type TransferPointDescription,
  type BackendName,
  type RendererName,
  type VoxelTypeName,
} from './scene-description.js';
export type { VptPageApi, PageRenderResult, RenderTimings, BackendSummary, PostModule } from './page/types.js';
