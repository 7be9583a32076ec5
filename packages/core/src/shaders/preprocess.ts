/**
 * A tiny line preprocessor applied identically to the GLSL and the WGSL kernels, so a
 * feature variant contains only the code it needs (WGSL has no preprocessor, and code
 * that names a texture the variant does not bind would not compile).
 *
 *   #if EXPR / #elif EXPR / #else / #endif   (nestable, each on its own line)
 *   EXPR := TERM (('&&' | '||') TERM)*      evaluated left to right, && binding tighter
 *   TERM := '!'? NAME | NAME OP INTEGER     OP one of == != >= <= > <
 *
 * NAME must be a key of `flags` (booleans count as 1/0); an unknown name is a programming
 * error and throws. `options.defer` names flags that a later run resolves (a renderer cuts its
 * own variant, then the context adds VPT_GUIDES): an `#if NAME` / `#if !NAME` on a deferred
 * name is kept with its `#else` / `#endif` lines, and both branches are kept for that run.
 */
export type Flags = Readonly<Record<string, boolean | number>>;

const DIRECTIVE = /^\s*#(if|elif|else|endif)\b(.*)$/;

function evalTerm(term: string, flags: Flags): boolean {
  const t = term.trim();
  const value = (name: string): number => {
    if (!(name in flags)) throw new Error(`preprocess: unknown flag "${name}"`);
    const v = flags[name];
    return typeof v === 'boolean' ? (v ? 1 : 0) : v;
  };
  let m = /^(!?)\s*([A-Za-z_][A-Za-z0-9_]*)$/.exec(t);
  if (m) return m[1] ? value(m[2]) === 0 : value(m[2]) !== 0;
  m = /^([A-Za-z_][A-Za-z0-9_]*)\s*(==|!=|>=|<=|>|<)\s*(-?\d+)$/.exec(t);
  if (!m) throw new Error(`preprocess: cannot parse condition "${t}"`);
  const a = value(m[1]),
    b = Number(m[3]);
  switch (m[2]) {
    case '==':
      return a === b;
    case '!=':
      return a !== b;
    case '>=':
      return a >= b;
    case '<=':
      return a <= b;
    case '>':
      return a > b;
    default:
      return a < b;
  }
}

export function evalCondition(expr: string, flags: Flags): boolean {
  return expr.split('||').some((conj) => conj.split('&&').every((term) => evalTerm(term, flags)));
}

export function preprocess(source: string, flags: Flags, options: { defer?: readonly string[] } = {}): string {
  // One frame per open #if: is this branch emitting, has any branch been taken, was the parent emitting,
  // and is it a deferred #if, kept for a later run.
  const stack: { active: boolean; taken: boolean; parent: boolean; deferred?: boolean }[] = [];
  const deferred = (expr: string) => {
    const name = /^\s*!?\s*([A-Za-z_][A-Za-z0-9_]*)\s*$/.exec(expr)?.[1];
    return name !== undefined && (options.defer ?? []).includes(name);
  };
  const out: string[] = [];
  const emitting = () => (stack.length === 0 ? true : stack[stack.length - 1].active);
  source.split('\n').forEach((line, n) => {
    const m = DIRECTIVE.exec(line);
    if (!m) {
      if (emitting()) out.push(line);
      return;
    }
    const [, kind, rest] = m;
    const where = `line ${n + 1}`;
    if (kind === 'if' && deferred(rest)) {
      const parent = emitting();
      if (parent) out.push(line);
      stack.push({ active: parent, taken: false, parent, deferred: true });
    } else if (kind === 'if') {
      const parent = emitting();
      const c = parent && evalCondition(rest, flags);
      stack.push({ active: c, taken: c, parent });
    } else {
      const top = stack[stack.length - 1];
      if (!top) throw new Error(`preprocess: #${kind} without #if (${where})`);
      if (top.deferred) {
        if (kind === 'elif') throw new Error(`preprocess: #elif after a deferred #if (${where})`);
        if (top.parent) out.push(line);
        if (kind === 'endif') stack.pop();
      } else if (kind === 'elif') {
        const c = top.parent && !top.taken && evalCondition(rest, flags);
        top.active = c;
        top.taken ||= c;
      } else if (kind === 'else') {
        top.active = top.parent && !top.taken;
        top.taken = true;
      } else {
        stack.pop();
      }
    }
  });
  if (stack.length) throw new Error('preprocess: unterminated #if');
  return out.join('\n');
}
