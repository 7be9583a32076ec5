/** Compiling and linking GLSL ES 3.0 programs, with errors a person can act on. */
import { VptError } from '../../errors.js';

/** Lines shown either side of each line the info log points at. */
const CONTEXT_LINES = 3;

/**
 * The source lines around the lines an info log names ("ERROR: 0:12: …"), numbered as
 * the compiler counts them (the prelude included). Falls back to the first lines.
 */
export function excerptSource(source: string, log: string): string {
  const lines = source.split('\n');
  const wanted = new Set<number>();
  for (const m of log.matchAll(/(?:ERROR|WARNING):\s*\d+:(\d+)/g)) {
    const n = Number(m[1]);
    for (let i = n - CONTEXT_LINES; i <= n + CONTEXT_LINES; i++) if (i >= 1 && i <= lines.length) wanted.add(i);
  }
  if (wanted.size === 0) for (let i = 1; i <= Math.min(lines.length, 2 * CONTEXT_LINES + 1); i++) wanted.add(i);
  const width = String(lines.length).length;
  const out: string[] = [];
  let prev = 0;
  for (const n of [...wanted].sort((a, b) => a - b)) {
    if (prev && n !== prev + 1) out.push('  ...');
    out.push(`${String(n).padStart(width)}| ${lines[n - 1]}`);
    prev = n;
  }
  return out.join('\n');
}

export function compileShader(gl: WebGL2RenderingContext, type: number, source: string, label: string): WebGLShader {
  const shader = gl.createShader(type);
  if (!shader)
    throw new VptError('shader-compile', `Pass "${label}": could not create a shader object (is the context lost?)`);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS) && !gl.isContextLost()) {
    const log = (gl.getShaderInfoLog(shader) ?? '').trim();
    gl.deleteShader(shader);
    const stage = type === gl.VERTEX_SHADER ? 'vertex' : 'fragment';
    throw new VptError(
      'shader-compile',
      `Pass "${label}": ${stage} shader failed to compile:\n${log}\n${excerptSource(source, log)}`,
    );
  }
  return shader;
}

/** A program whose compile and link were issued but whose status was not asked yet. */
export interface PendingProgram {
  readonly program: WebGLProgram;
  readonly fragment: WebGLShader;
  readonly fragmentSource: string;
  readonly label: string;
}

/**
 * Issue the compile and link of a program without asking for its status, which would wait
 * for the driver: with KHR_parallel_shader_compile the driver works on several at once.
 */
export function startProgram(
  gl: WebGL2RenderingContext,
  vertex: WebGLShader,
  fragmentSource: string,
  label: string,
): PendingProgram {
  const fragment = gl.createShader(gl.FRAGMENT_SHADER);
  if (!fragment)
    throw new VptError('shader-compile', `Pass "${label}": could not create a shader object (is the context lost?)`);
  gl.shaderSource(fragment, fragmentSource);
  gl.compileShader(fragment);
  const program = gl.createProgram();
  if (!program) {
    gl.deleteShader(fragment);
    throw new VptError('shader-compile', `Pass "${label}": could not create a program object (is the context lost?)`);
  }
  gl.attachShader(program, vertex);
  gl.attachShader(program, fragment);
  return { program, fragment, fragmentSource, label };
}

/** Link a started program (after every program of a batch was compiled: the driver overlaps them). */
export function linkStarted(gl: WebGL2RenderingContext, p: PendingProgram): void {
  gl.linkProgram(p.program);
}

/** The verdict on a started and linked program: the program, or the compile or link log as a VptError. */
export function finishProgram(gl: WebGL2RenderingContext, p: PendingProgram): WebGLProgram {
  const { program, fragment, fragmentSource, label } = p;
  if (!gl.getShaderParameter(fragment, gl.COMPILE_STATUS) && !gl.isContextLost()) {
    const log = (gl.getShaderInfoLog(fragment) ?? '').trim();
    gl.deleteProgram(program);
    gl.deleteShader(fragment);
    throw new VptError(
      'shader-compile',
      `Pass "${label}": fragment shader failed to compile:\n${log}\n${excerptSource(fragmentSource, log)}`,
    );
  }
  // The program keeps what it needs; the fragment shader object is not reused.
  gl.detachShader(program, fragment);
  gl.deleteShader(fragment);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS) && !gl.isContextLost()) {
    const log = (gl.getProgramInfoLog(program) ?? '').trim();
    gl.deleteProgram(program);
    throw new VptError(
      'shader-compile',
      `Pass "${label}": program failed to link:\n${log}\n${excerptSource(fragmentSource, log)}`,
    );
  }
  return program;
}

/** Link a program from a shared vertex shader and a freshly compiled fragment shader. */
export function linkProgram(
  gl: WebGL2RenderingContext,
  vertex: WebGLShader,
  fragmentSource: string,
  label: string,
): WebGLProgram {
  const pending = startProgram(gl, vertex, fragmentSource, label);
  linkStarted(gl, pending);
  return finishProgram(gl, pending);
}
