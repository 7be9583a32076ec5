/**
 * Compiled pass programs, cached by their full fragment source. The source already
 * holds everything that changes the program (the kernel, defines, uniform block,
 * texture declarations, outputs), so equal sources can share one program.
 */
import type { PassDescriptor } from '../backend.js';
import { FLIP_Y_UNIFORM, FULLSCREEN_VERTEX_SHADER, TARGET_SIZE_UNIFORM, buildFragmentSource } from './glsl-prelude.js';
import { compileShader, finishProgram, linkStarted, startProgram, type PendingProgram } from './shader-program.js';

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

  /** Programs compileAhead issued that no get() has claimed yet, by fragment source. */
  private readonly pending = new Map<string, PendingProgram>();
  /** KHR_parallel_shader_compile's COMPLETION_STATUS_KHR, where offered. */
  private readonly completionStatus: number | null;

  constructor(private readonly gl: WebGL2RenderingContext) {
    const ext = gl.getExtension('KHR_parallel_shader_compile') as { COMPLETION_STATUS_KHR: number } | null;
    this.completionStatus = ext ? ext.COMPLETION_STATUS_KHR : null;
  }

  private vertexShader(): WebGLShader {
    const gl = this.gl;
    return (this.vertex ??= compileShader(gl, gl.VERTEX_SHADER, FULLSCREEN_VERTEX_SHADER, 'vpt full-screen triangle'));
  }

  /**
   * Issue the compile of every fragment shader first, then every link, so the driver can work
   * on them together; resolve once COMPLETION_STATUS_KHR says each is done (polled, so the
   * thread is free meanwhile). Without the extension it resolves at once and get() waits.
   * Status and logs are left to get(), which reports a failure as before.
   */
  async compileAhead(descs: readonly PassDescriptor[]): Promise<void> {
    const gl = this.gl;
    const started: PendingProgram[] = [];
    for (const desc of descs) {
      const source = buildFragmentSource(desc);
      if (this.entries.has(source) || this.pending.has(source)) continue;
      const p = startProgram(gl, this.vertexShader(), source, desc.label);
      this.pending.set(source, p);
      started.push(p);
    }
    for (const p of started) linkStarted(gl, p);
    const status = this.completionStatus;
    if (status === null) return;
    let waiting = started;
    while (waiting.length > 0 && !gl.isContextLost()) {
      await new Promise((r) => setTimeout(r, 2));
      // One that get() claimed (and waited for) or that was deleted is no longer awaited.
      waiting = waiting.filter(
        (p) => this.pending.get(p.fragmentSource) === p && !gl.getProgramParameter(p.program, status),
      );
    }
  }

  get(desc: PassDescriptor): ProgramEntry {
    const source = buildFragmentSource(desc);
    const hit = this.entries.get(source);
    if (hit) return hit;
    const gl = this.gl;
    let started = this.pending.get(source);
    this.pending.delete(source);
    if (!started) {
      started = startProgram(gl, this.vertexShader(), source, desc.label);
      linkStarted(gl, started);
    }
    const program = finishProgram(gl, started);

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
    for (const p of this.pending.values()) {
      gl.deleteProgram(p.program);
      gl.deleteShader(p.fragment);
    }
    if (this.vertex) gl.deleteShader(this.vertex);
    this.forget();
  }

  /** Drop every entry without GL calls: after a context loss the objects are already gone. */
  forget(): void {
    this.entries.clear();
    this.pending.clear();
    this.vertex = null;
  }
}
