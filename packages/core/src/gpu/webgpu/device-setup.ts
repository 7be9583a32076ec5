/**
 * Acquiring a WebGPU adapter and device: availability probe, the limits and features
 * vpt asks for, and the adapter description for benchmark records.
 */
import { VptError } from '../../errors.js';
import type { BackendInfo, BackendOptions } from '../backend.js';

export interface GpuDeviceHandle {
  /** Null for a device someone else requested (BackendOptions.device). */
  adapter: GPUAdapter | null;
  device: GPUDevice;
  info: BackendInfo;
}

function gpuOrNull(): GPU | null {
  return typeof navigator !== 'undefined' && 'gpu' in navigator && navigator.gpu ? navigator.gpu : null;
}

/** True when the browser exposes navigator.gpu and gives an adapter. */
export async function isWebGPUAvailable(): Promise<boolean> {
  const gpu = gpuOrNull();
  if (!gpu) return false;
  try {
    return (await gpu.requestAdapter()) !== null;
  } catch {
    return false;
  }
}

/**
 * Limits raised to the adapter's maxima. The defaults (2D 8192, 3D 2048, 32 bytes per
 * sample) are too small for large volumes and for MRT passes with several rgba32float
 * accumulation buffers; asking for the adapter's own values never fails.
 */
const RAISED_LIMITS = [
  'maxTextureDimension2D',
  'maxTextureDimension3D',
  'maxColorAttachments',
  'maxColorAttachmentBytesPerSample',
  'maxSampledTexturesPerShaderStage',
  'maxUniformBufferBindingSize',
  'maxBufferSize',
] as const;

const OPTIONAL_FEATURES = ['timestamp-query', 'texture-formats-tier1', 'float32-filterable'];

/** Request an adapter and a device, or throw VptError('no-backend'). */
export async function requestGpuDevice(
  options: Pick<BackendOptions, 'powerPreference'> = {},
): Promise<GpuDeviceHandle> {
  const gpu = gpuOrNull();
  if (!gpu) {
    throw new VptError(
      'no-backend',
      'WebGPU is not available: this browser has no navigator.gpu (needs a WebGPU-capable browser on a secure origin: https or localhost)',
    );
  }
  let adapter: GPUAdapter | null;
  try {
    adapter = await gpu.requestAdapter(
      options.powerPreference ? { powerPreference: options.powerPreference } : undefined,
    );
  } catch (e) {
    throw new VptError('no-backend', 'WebGPU is not available: navigator.gpu.requestAdapter() failed', { cause: e });
  }
  if (!adapter)
    throw new VptError(
      'no-backend',
      'WebGPU is not available: navigator.gpu.requestAdapter() returned no adapter (no supported GPU, or WebGPU is disabled)',
    );

  const requiredLimits: Record<string, number> = {};
  for (const name of RAISED_LIMITS) {
    const v = adapter.limits[name];
    if (typeof v === 'number') requiredLimits[name] = v;
  }
  // Optional features, asked for only when offered: timestamp queries let benchmarks time
  // passes on the GPU; 16-bit normalized textures ('texture-formats-tier1': r16unorm/r16snorm)
  // and filterable r32float ('float32-filterable') serve the volume's compact fast path.
  const requiredFeatures = OPTIONAL_FEATURES.filter((f) => adapter.features.has(f)) as GPUFeatureName[];
  let device: GPUDevice;
  try {
    device = await adapter.requestDevice({ label: 'vpt', requiredFeatures, requiredLimits });
  } catch (e) {
    throw new VptError('no-backend', 'WebGPU is not available: the adapter did not give a device', { cause: e });
  }
  return { adapter, device, info: adapterInfo(adapter) };
}

function adapterInfo(adapter: GPUAdapter): BackendInfo {
  // adapter.info is recent (Chrome 127); older browsers leave it out.
  const a: Partial<GPUAdapterInfo> = adapter.info ?? {};
  const description = a.description ?? '';
  const architecture = a.architecture ?? '';
  const renderer =
    description && architecture ? `${description} (${architecture})` : description || architecture || 'WebGPU adapter';
  return { kind: 'webgpu', renderer, vendor: a.vendor || 'unknown' };
}
