/**
 * The backend's GpuTexture / RenderTarget / GpuPass objects. Each remembers the device
 * generation it was made in: after a device loss and restore the GPU objects behind it
 * belong to a dead device, and the backend recognises such stale objects instead of
 * failing with a WebGPU validation error far from the cause.
 */
import type { GpuPass, GpuTexture, PassDescriptor, RenderTarget, TextureFormat } from '../backend.js';
import type { PipelineEntry } from './pipeline-cache.js';

export class WebGPUTexture implements GpuTexture {
  /** Made on first use; every pass binds the whole texture. */
  private cachedView: GPUTextureView | null = null;

  constructor(
    readonly dimension: '2d' | '3d',
    readonly width: number,
    readonly height: number,
    readonly depth: number,
    readonly format: TextureFormat,
    readonly label: string,
    /** Null when made while the device was lost. */
    public handle: GPUTexture | null,
    readonly generation: number,
  ) {}

  view(): GPUTextureView {
    if (!this.handle) throw new Error(`texture "${this.label}" has no GPU texture`);
    this.cachedView ??= this.handle.createView({ label: this.label });
    return this.cachedView;
  }

  destroy(): void {
    this.handle?.destroy();
    this.handle = null;
    this.cachedView = null;
  }
}

export class WebGPURenderTarget implements RenderTarget {
  constructor(
    readonly width: number,
    readonly height: number,
    readonly textures: readonly WebGPUTexture[],
    readonly label: string,
    readonly generation: number,
  ) {}
}

export class WebGPUPass implements GpuPass {
  constructor(
    readonly descriptor: PassDescriptor,
    /** Shader module, layouts and pipelines; shared by equal descriptors. Null when made while lost. */
    readonly program: PipelineEntry | null,
    readonly generation: number,
  ) {}
}
