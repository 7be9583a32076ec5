/** Acquiring the WebGL 2 context vpt needs and reading what it offers. */
import { VptError } from '../../errors.js';
import type { BackendInfo, BackendLimits } from '../backend.js';

/**
 * No antialiasing, depth or stencil: every pass is one full-screen triangle. The canvas
 * keeps its content between frames (preserveDrawingBuffer) so a presented image stays
 * readable and re-presentable, and alpha is not premultiplied (vpt writes straight alpha).
 */
export const CONTEXT_ATTRIBUTES: WebGLContextAttributes = {
  antialias: false,
  depth: false,
  stencil: false,
  alpha: true,
  premultipliedAlpha: false,
  preserveDrawingBuffer: true,
};

export function acquireContext(canvas: HTMLCanvasElement | OffscreenCanvas): WebGL2RenderingContext {
  let gl: WebGL2RenderingContext | null = null;
  try {
    gl = (canvas as HTMLCanvasElement).getContext('webgl2', CONTEXT_ATTRIBUTES);
  } catch (e) {
    throw new VptError('no-backend', 'WebGL 2 is not available: creating a webgl2 context failed', { cause: e });
  }
  if (!gl) {
    throw new VptError(
      'no-backend',
      'WebGL 2 is not available: canvas.getContext("webgl2") returned null (unsupported browser, disabled GPU, or the canvas already has another context)',
    );
  }
  return gl;
}

/** Float render targets are the core of vpt's accumulation buffers; without them nothing works. */
export function requireColorBufferFloat(gl: WebGL2RenderingContext): void {
  if (!gl.getExtension('EXT_color_buffer_float')) {
    throw new VptError(
      'missing-extension',
      'WebGL 2 without the EXT_color_buffer_float extension: vpt needs float render targets (R32F, RGBA32F)',
    );
  }
}

export interface GlLimits extends BackendLimits {
  maxColorAttachments: number;
  maxTextureUnits: number;
  maxUniformBlockSize: number;
}

export function readLimits(gl: WebGL2RenderingContext): GlLimits {
  return {
    maxTextureDimension2D: gl.getParameter(gl.MAX_TEXTURE_SIZE) as number,
    maxTextureDimension3D: gl.getParameter(gl.MAX_3D_TEXTURE_SIZE) as number,
    maxColorAttachments: Math.min(
      gl.getParameter(gl.MAX_COLOR_ATTACHMENTS) as number,
      gl.getParameter(gl.MAX_DRAW_BUFFERS) as number,
    ),
    maxTextureUnits: gl.getParameter(gl.MAX_TEXTURE_IMAGE_UNITS) as number,
    maxUniformBlockSize: gl.getParameter(gl.MAX_UNIFORM_BLOCK_SIZE) as number,
  };
}

export function readInfo(gl: WebGL2RenderingContext): BackendInfo {
  // Recent browsers report the unmasked strings through RENDERER/VENDOR directly and
  // warn about the extension, so fall back to those when it is absent.
  const dbg = gl.getExtension('WEBGL_debug_renderer_info');
  const renderer = dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  const vendor = dbg ? gl.getParameter(dbg.UNMASKED_VENDOR_WEBGL) : gl.getParameter(gl.VENDOR);
  return { kind: 'webgl2', renderer: String(renderer ?? ''), vendor: String(vendor ?? '') };
}
