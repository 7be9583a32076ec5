export { VptWebGPUCompositor, type VptWebGPUCompositorOptions } from './webgpu-compositor.js';
export { VptVolume, vptViewOf, type VptVolumeOptions, type VptVolumeScene, type VptView } from './vpt-volume.js';

/**
 * The device limits vpt's passes need raised above WebGPU's defaults (several rgba32float
 * colour attachments: 48 bytes per sample or more), at the adapter's own maxima; pass them
 * to the renderer: `new WebGPURenderer({ requiredLimits: vptRequiredLimits(adapter) })`.
 */
export function vptRequiredLimits(adapter: GPUAdapter): Record<string, number> {
  const out: Record<string, number> = {};
  for (const name of ['maxColorAttachmentBytesPerSample', 'maxColorAttachments', 'maxTextureDimension3D'] as const)
    out[name] = adapter.limits[name];
  return out;
}
