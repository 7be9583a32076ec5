/**
 * Compiled pass programs, cached by their full fragment source. The source already
 * holds everything that changes the program (the kernel, defines, uniform block,
 * texture declarations, outputs), so equal sources can share one program.
 */
import type { PassDescriptor } from '../backend.js';
import { FLIP_Y_UNIFORM, FULLSCREEN_VERTEX_SHADER, TARGET_SIZE_UNIFORM, buildFragmentSource } from './glsl-prelude.js';
import { compileShader, linkProgram } from './shader-program.js';

/** The UBO binding point every pass's uniform block is bound to. */
export const UNIFORM_BLOCK_BINDING = 0;

export interface ProgramEntry {
  readonly program: WebGLProgram;
  readonly targetSize: WebGLUniformLocation | null;
  readonly flipY: WebGLUniformLocation | null;
  /** The pass's uniform buffer (null when the layout has no fields or the compiler dropped the block). */
  readonly ubo: WebGLBuffer | null;
  /** Current byte size of `ubo`'s store, so same-size uploads use bufferSubData. */
  uboSize: number;
}

export class ProgramCache {
  private readonly entries = new Map<string, ProgramEntry>();
  private vertex: WebGLShader | null = null;

  constructor(private readonly gl: WebGL2RenderingContext) {}

  get(desc: PassDescriptor): ProgramEntry {
    const source = buildFragmentSource(desc);
    const hit = this.entries.get(source);
    if (hit) return hit;
    const gl = this.gl;
    this.vertex ??= compileShader(gl, gl.VERTEX_SHADER, FULLSCREEN_VERTEX_SHADER, 'vpt full-screen triangle');
    const program = linkProgram(gl, this.vertex, source, desc.label);

    let ubo: WebGLBuffer | null = null;
    if (desc.uniforms.fields.length > 0) {
      const block = gl.getUniformBlockIndex(program, `${desc.uniforms.structName}Block`);
      if (block !== gl.INVALID_INDEX) {
        gl.uniformBlockBinding(program, block, UNIFORM_BLOCK_BINDING);
        ubo = gl.createBuffer();
      }
    }
    // Sampler k reads texture unit k; this is program state, so set it once here.
    gl.useProgram(program);
    desc.textures.forEach((t, k) => {
      const loc = gl.getUniformLocation(program, t.name);
      if (loc) gl.uniform1i(loc, k);
    });
    const entry: ProgramEntry = {
      program,
      targetSize: gl.getUniformLocation(program, TARGET_SIZE_UNIFORM),
      flipY: gl.getUniformLocation(program, FLIP_Y_UNIFORM),
      ubo,
      uboSize: 0,
    };
    this.entries.set(source, entry);
    return entry;
  }

  /** Delete every program, buffer and shader (used by dispose()). */
  deleteAll(): void {
    const gl = this.gl;
    for (const e of this.entries.values()) {
      gl.deleteProgram(e.program);
      if (e.ubo) gl.deleteBuffer(e.ubo);
    }
    if (this.vertex) gl.deleteShader(this.vertex);
    this.forget();
  }

  /** Drop every entry without GL calls: after a context loss the objects are already gone. */
  forget(): void {
    this.entries.clear();
    this.vertex = null;
  }
}
