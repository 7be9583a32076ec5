// The one command-line parser of vpt's CLIs and scripts: node:util parseArgs in strict
// mode, driven by an option table that also writes the usage text. Plain JavaScript
// (types in index.d.ts) so that scripts run before any build (`pnpm bench --help`,
// `pnpm data:fetch`) can import it; it depends on nothing but Node.
import { parseArgs } from 'node:util';

/** Bad command-line input; `code` says which kind, the message names the flag or argument. */
export class CliArgsError extends Error {
  constructor(code, message) {
    super(message);
    this.name = 'CliArgsError';
    this.code = code;
  }
}

const HELP = { type: 'boolean', short: 'h', description: 'print this help and exit' };
const INTEGER = /^[+-]?\d+$/;
const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i;

function rangeText(o) {
  if (o.min !== undefined && o.max !== undefined) return ` from ${o.min} to ${o.max}`;
  if (o.min !== undefined) return ` >= ${o.min}`;
  if (o.max !== undefined) return ` <= ${o.max}`;
  return '';
}

/** Convert one raw string to the option's type; `label` ("--seed", "ROUNDS") names it in errors. */
function convert(o, label, raw) {
  switch (o.type) {
    case 'string':
      if (o.choices && !o.choices.includes(raw))
        throw new CliArgsError('bad-value', `${label} must be one of ${o.choices.join(', ')}, got "${raw}"`);
      return raw;
    case 'integer':
    case 'number': {
      const text = raw.trim();
      const n = Number(text);
      const ok = o.type === 'integer' ? INTEGER.test(text) && Number.isSafeInteger(n) : DECIMAL.test(text);
      if (!ok || !Number.isFinite(n) || (o.min !== undefined && n < o.min) || (o.max !== undefined && n > o.max))
        throw new CliArgsError(
          'bad-value',
          `${label} must be ${o.type === 'integer' ? 'an integer' : 'a number'}${rangeText(o)}, got "${raw}"`,
        );
      return n;
    }
    case 'list': {
      const items = raw
        .split(o.separator ?? ',')
        .map((s) => s.trim())
        .filter((s) => s !== '');
      const unknown = o.choices ? items.filter((s) => !o.choices.includes(s)) : [];
      if (unknown.length)
        throw new CliArgsError(
          'bad-value',
          `${label}: unknown ${unknown.map((s) => `"${s}"`).join(', ')} (known: ${o.choices.join(', ')})`,
        );
      return items;
    }
    case 'json':
      try {
        return JSON.parse(raw);
      } catch (e) {
        throw new CliArgsError('bad-value', `${label} must be JSON: ${e instanceof Error ? e.message : e}`);
      }
    default:
      throw new Error(`option table: ${label} has an unknown type "${o.type}"`);
  }
}

function nodeOptions(spec) {
  const options = { help: HELP };
  for (const [name, o] of Object.entries(spec.options ?? {}))
    options[name] = { type: o.type === 'boolean' ? 'boolean' : 'string', ...(o.short ? { short: o.short } : {}) };
  return options;
}

/** Whether -h/--help is among the options (even next to unknown or bad ones: help wins). */
function asksForHelp(spec, args) {
  const { tokens } = parseArgs({
    args,
    options: nodeOptions(spec),
    strict: false,
    allowPositionals: true,
    tokens: true,
  });
  return tokens.some((t) => t.kind === 'option' && t.name === 'help');
}

/** node:util's parse errors as CliArgsError codes (an invalid value is a missing one or one a flag does not take). */
function parseErrorCode(e) {
  if (e?.code === 'ERR_PARSE_ARGS_UNKNOWN_OPTION') return 'unknown-option';
  if (e?.code === 'ERR_PARSE_ARGS_UNEXPECTED_POSITIONAL') return 'unexpected-argument';
  if (e?.code === 'ERR_PARSE_ARGS_INVALID_OPTION_VALUE')
    return /argument missing|ambiguous/.test(String(e.message)) ? 'missing-value' : 'bad-value';
  return undefined;
}

/**
 * Parse `argv` (without node and the script) against `spec`. Bare `--` tokens are dropped:
 * pnpm forwards them from `pnpm x -- --flag`, and no vpt CLI takes an argument starting with
 * "-". Returns `{ help: true }` when -h/--help is given; throws CliArgsError on bad input.
 */
export function parseCli(spec, argv) {
  const args = argv.filter((a) => a !== '--');
  if (asksForHelp(spec, args)) return { help: true, values: {}, positionals: [] };
  const positionalSpecs = spec.positionals ?? [];
  const variadic = positionalSpecs.some((p) => p.variadic);
  let parsed;
  try {
    parsed = parseArgs({
      args,
      options: nodeOptions(spec),
      strict: true,
      allowPositionals: positionalSpecs.length > 0,
    });
  } catch (e) {
    const code = parseErrorCode(e);
    if (!code) throw e;
    // Node's message names the flag; its advice about `--` does not apply here (see above).
    throw new CliArgsError(code, String(e.message).replace(/\. To specify a positional argument.*$/s, ''));
  }
  const values = {};
  for (const [name, o] of Object.entries(spec.options ?? {})) {
    const raw = parsed.values[name];
    if (o.type === 'boolean') values[name] = raw === true;
    else if (raw !== undefined) values[name] = convert(o, `--${name}`, raw);
    else if (o.default !== undefined) values[name] = Array.isArray(o.default) ? [...o.default] : o.default;
  }
  const given = parsed.positionals;
  if (!variadic && given.length > positionalSpecs.length)
    throw new CliArgsError(
      'unexpected-argument',
      `unexpected argument${given.length - positionalSpecs.length > 1 ? 's' : ''}: ${given.slice(positionalSpecs.length).join(' ')}`,
    );
  positionalSpecs.forEach((p, i) => {
    const raws = p.variadic ? given.slice(i) : given.slice(i, i + 1);
    if (raws.length === 0) {
      if (p.required) throw new CliArgsError('missing-argument', `missing ${p.name}`);
      if (p.default !== undefined) values[p.key] = Array.isArray(p.default) ? [...p.default] : p.default;
      else if (p.variadic) values[p.key] = [];
      return;
    }
    const converted = raws.map((r) => convert(p, p.name, r));
    values[p.key] = p.variadic ? converted : converted[0];
  });
  return { help: false, values, positionals: given };
}

function valueName(o) {
  if (o.valueName) return o.valueName;
  if (o.type === 'string' && o.choices) return o.choices.join('|');
  return { string: 'TEXT', integer: 'N', number: 'X', list: 'A,B', json: 'JSON' }[o.type] ?? '';
}

function defaultText(o) {
  if (o.default === undefined || o.type === 'boolean') return '';
  return ` (default ${Array.isArray(o.default) ? o.default.join(o.separator ?? ',') : o.default})`;
}

/** The usage text: synopsis, summary, one line per option (from the table), epilog. */
export function cliUsage(spec) {
  const rows = Object.entries({ ...(spec.options ?? {}), help: HELP }).map(([name, o]) => [
    `${o.short ? `-${o.short}, ` : '    '}--${name}${o.type === 'boolean' ? '' : ` ${valueName(o)}`}`,
    `${o.description ?? ''}${defaultText(o)}`,
  ]);
  for (const p of spec.positionals ?? [])
    rows.unshift([`${p.name}${p.variadic ? '…' : ''}`, `${p.description ?? ''}${defaultText(p)}`]);
  const width = Math.min(34, Math.max(...rows.map(([left]) => left.length)) + 2);
  const lines = rows.map(([left, right]) =>
    left.length + 2 > width ? `  ${left}\n  ${' '.repeat(width)}${right}` : `  ${left.padEnd(width)}${right}`,
  );
  return [
    `Usage: ${spec.name}${spec.synopsis ? ` ${spec.synopsis}` : ''}`,
    ...(spec.summary ? [spec.summary] : []),
    '',
    spec.positionals?.length ? 'Arguments and options:' : 'Options:',
    ...lines,
    ...(spec.epilog ? ['', spec.epilog] : []),
  ].join('\n');
}

/**
 * parseCli for a script's entry point: prints the usage and exits 0 on --help, prints
 * "NAME: message" and exits 2 on bad input, otherwise returns the parsed values.
 */
export function parseCliOrExit(spec, argv = process.argv.slice(2)) {
  let parsed;
  try {
    parsed = parseCli(spec, argv);
  } catch (e) {
    if (!(e instanceof CliArgsError)) throw e;
    console.error(`${spec.name}: ${e.message} (--help lists the options)`);
    process.exit(2);
  }
  if (parsed.help) {
    console.log(cliUsage(spec));
    process.exit(0);
  }
  return parsed.values;
}
