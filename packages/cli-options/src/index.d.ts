// Types of index.js: an option table (CliSpec) and what parseCli makes of it.

export type CliArgsErrorCode =
  'unknown-option' | 'missing-value' | 'bad-value' | 'unexpected-argument' | 'missing-argument';

export declare class CliArgsError extends Error {
  readonly code: CliArgsErrorCode;
  constructor(code: CliArgsErrorCode, message: string);
}

interface Described {
  /** One line for the usage text. */
  readonly description?: string;
  /** The value's name in the usage text (default from the type: N, X, TEXT, A,B, JSON). */
  readonly valueName?: string;
}
interface Ranged {
  /** Inclusive bounds; a value outside them is refused, naming the flag. */
  readonly min?: number;
  readonly max?: number;
}

export type CliValueSpec =
  | (Described & { readonly type: 'string'; readonly default?: string; readonly choices?: readonly string[] })
  | (Described & Ranged & { readonly type: 'integer' | 'number'; readonly default?: number })
  | (Described & {
      /** Comma-separated (or `separator`-separated) items, each one of `choices` when given. */
      readonly type: 'list';
      readonly default?: readonly string[];
      readonly choices?: readonly string[];
      readonly separator?: string;
    })
  | (Described & { readonly type: 'json'; readonly default?: unknown });

export type CliOptionSpec = (CliValueSpec | (Described & { readonly type: 'boolean' })) & {
  /** One-letter alias (-o). */
  readonly short?: string;
};

export type CliPositionalSpec = CliValueSpec & {
  /** Where parseCli puts the value. */
  readonly key: string;
  /** The name in the usage text and in errors (VARIANTS, scene.json). */
  readonly name: string;
  readonly required?: boolean;
  /** The last positional only: takes every remaining argument (an array). */
  readonly variadic?: boolean;
};

export interface CliSpec {
  /** The command as a user types it (vpt-render, pnpm bench, node scripts/x.mjs). */
  readonly name: string;
  /** What follows the name on the usage line. */
  readonly synopsis?: string;
  readonly summary?: string;
  readonly options?: { readonly [name: string]: CliOptionSpec };
  readonly positionals?: readonly CliPositionalSpec[];
  /** Text after the option list. */
  readonly epilog?: string;
}

type Scalar<O> = O extends { type: 'boolean' }
  ? boolean
  : O extends { type: 'integer' | 'number' }
    ? number
    : O extends { type: 'string'; choices: readonly (infer C)[] }
      ? C
      : O extends { type: 'string' }
        ? string
        : O extends { type: 'list'; choices: readonly (infer C)[] }
          ? C[]
          : O extends { type: 'list' }
            ? string[]
            : unknown;

/** An option's parsed value: booleans are always there, others when given or defaulted. */
export type CliOptionValue<O> = O extends { type: 'boolean' } | { default: unknown }
  ? Scalar<O>
  : Scalar<O> | undefined;
type PositionalValue<P> = P extends { variadic: true }
  ? Scalar<P>[]
  : P extends { required: true } | { default: unknown }
    ? Scalar<P>
    : Scalar<P> | undefined;

export type CliValues<S extends CliSpec> = {
  -readonly [K in keyof NonNullable<S['options']>]: CliOptionValue<NonNullable<S['options']>[K]>;
} & (S['positionals'] extends readonly (infer P)[]
  ? { [K in P extends { key: infer Key extends string } ? Key : never]: PositionalValue<Extract<P, { key: K }>> }
  : unknown);

export type CliParse<S extends CliSpec> =
  | { help: true; values: Record<string, never>; positionals: string[] }
  | { help: false; values: CliValues<S>; positionals: string[] };

/** Parse argv (no node, no script) strictly against the table; -h/--help wins over everything else. */
export declare function parseCli<const S extends CliSpec>(spec: S, argv: readonly string[]): CliParse<S>;
/** The usage text generated from the table. */
export declare function cliUsage(spec: CliSpec): string;
/** parseCli for an entry point: usage + exit 0 on --help, "NAME: message" + exit 2 on bad input. */
export declare function parseCliOrExit<const S extends CliSpec>(spec: S, argv?: readonly string[]): CliValues<S>;
