/** Turn WGSL compiler messages into the readable log a VptError('shader-compile') carries. */

/** The fields of GPUCompilationMessage this report uses (plain objects work too). */
export interface CompileMessage {
  readonly type: GPUCompilationMessageType;
  readonly message: string;
  readonly lineNum: number;
  readonly linePos: number;
}

/**
 * "Pass "label": WGSL compilation failed" (or "…failed validation") followed by one entry per message: its kind,
 * line:column and text, then the numbered source line it points at (line numbers count
 * the whole generated module, prelude included). `extra` is a validation error that
 * came without a position (pipeline creation, layout mismatch).
 */
export function formatCompileError(
  label: string,
  source: string,
  messages: readonly CompileMessage[],
  extra?: string,
): string {
  const lines = source.split('\n');
  const width = String(lines.length).length;
  const compiled = !messages.some((m) => m.type === 'error');
  const out = [
    `Pass "${label}": ${compiled ? 'the kernel compiled but failed validation' : 'WGSL compilation failed'}`,
  ];
  for (const m of messages) {
    if (m.type === 'info') continue;
    if (m.lineNum > 0) {
      out.push(`${m.type} at line ${m.lineNum}:${m.linePos}: ${m.message}`);
      for (let n = Math.max(1, m.lineNum - 1); n <= Math.min(lines.length, m.lineNum + 1); n++) {
        out.push(`${n === m.lineNum ? '>' : ' '} ${String(n).padStart(width)}| ${lines[n - 1]}`);
      }
    } else out.push(`${m.type}: ${m.message}`);
  }
  if (extra) out.push(extra);
  return out.join('\n');
}
