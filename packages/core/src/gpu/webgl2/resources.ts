/**
 * The backend's GpuTexture / RenderTarget / GpuPass objects. Each remembers the context
 * generation it was made in: after a context loss and restore the GL objects behind it
 * are gone, and the backend recognises such stale objects instead of failing cryptically.
 */
import type { GpuPass, GpuTexture, PassDescriptor, RenderTarget, TextureFormat } from '../backend.js';
import type { ProgramEntry } from './program-cache.js';

export class WebGL2Texture implements GpuTexture {
  constructor(
    readonly dimension: '2d' | '3d',
    readonly width: number,
    readonly height: number,
    readonly depth: number,
    readonly format: TextureFormat,
    readonly label: string,
    /** Null when made while the context was lost. */
    public handle: WebGLTexture | null,
    readonly generation: number,
  ) {}
}

export class WebGL2RenderTarget implements RenderTarget {
  constructor(
    readonly width: number,
    readonly height: number,
    readonly textures: readonly WebGL2Texture[],
    readonly label: string,
    public framebuffer: WebGLFramebuffer | null,
    readonly generation: number,
  ) {}
}

export class WebGL2Pass implements GpuPass {
  constructor(
    readonly descriptor: PassDescriptor,
    /** Null when made while the context was lost. */
    readonly program: ProgramEntry | null,
    readonly generation: number,
  ) {}
}
