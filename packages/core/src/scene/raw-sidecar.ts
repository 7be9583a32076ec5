/**
 * The one reader of headerless raw volumes and their JSON sidecars (the data folder's
 * format: dims, voxel_type, spacing, endianness, value_range, axes, file). @vpt/loaders,
 * the viewer's fallback loader and the headless page all call it, so sidecar semantics
 * (an inverted value_range, byte order, axes, dims from a file name) live here only. No
 * fetching and no dependencies beyond core's errors: callers bring the text and the bytes.
 */
import { VptError } from '../errors.js';
import type { VoxelArray, VoxelType } from './volume.js';

export const RAW_VOXEL_TYPES: readonly VoxelType[] = ['uint8', 'uint16', 'int16', 'float32'];
const ARRAYS = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array } as const;

/** 2^32 voxels: past this, 32-bit sizes (GPU APIs, C readers) wrap; a header claiming it lies or is beyond reach. */
export const MAX_RAW_VOXELS = 0x100000000;

/** What is wrong with a raw header or its bytes (the same words as @vpt/loaders' LoaderError reasons). */
export type RawReadReason = 'bad-header' | 'unsupported' | 'empty' | 'overflow' | 'truncated';

/** A raw header or raw file that cannot be read; code 'load-failed', `reason` says why. */
export class RawReadError extends VptError {
  readonly reason: RawReadReason;
  constructor(reason: RawReadReason, message: string, options?: { cause?: unknown }) {
    super('load-failed', message, options);
    this.name = 'RawReadError';
    this.reason = reason;
  }
}

/** What the bytes of a raw file need to be read. */
export interface RawHeader {
  dims: [number, number, number];
  type: VoxelType;
  spacing: [number, number, number];
  endianness: 'little' | 'big';
}

/** A parsed sidecar: the header, plus what else it says. */
export interface RawSidecar extends RawHeader {
  /** The raw file's name (the sidecar's `file`); see rawFileBeside. */
  file?: string;
  /** The values that map to 0 and 1; min > max is a deliberate inverted mapping. */
  valueRange?: [number, number];
  /** The sidecar's `axes` ('PIR'…): the anatomical direction (RAS+) each index axis runs toward. */
  axisCodes?: string;
  /** title, modality, units, spacingUnits, orientation, value_range, sha256, license, source, axisCodes, space. */
  meta: Record<string, unknown>;
}

/**
 * Dims straight from a header: every one a positive integer, and a voxel count that can
 * be addressed. Zero is 'empty' (nothing to draw), a product ≥ 2^32 is 'overflow'.
 */
export function checkRawDims(
  dims: readonly number[],
  name: string,
  source = 'header',
): asserts dims is [number, number, number] {
  const shown = `[${dims.join(' × ')}]`;
  if (dims.length !== 3 || dims.some((d) => typeof d !== 'number' || !Number.isFinite(d) || !Number.isInteger(d))) {
    throw new RawReadError(
      'bad-header',
      `${name}: the ${source} gives dims ${shown}; they must be three whole numbers`,
    );
  }
  if (dims.some((d) => d < 0))
    throw new RawReadError('bad-header', `${name}: the ${source} gives negative dims ${shown}`);
  if (dims.some((d) => d === 0))
    throw new RawReadError('empty', `${name}: the ${source} gives dims ${shown}: the volume is empty`);
  const count = dims[0] * dims[1] * dims[2];
  if (count >= MAX_RAW_VOXELS) {
    throw new RawReadError(
      'overflow',
      `${name}: the ${source} gives dims ${shown} = ${count.toExponential(3)} voxels, past the 2^32 a volume can address; the header is probably corrupt`,
    );
  }
}

/**
 * What to do about headerless raw data, in every way a user can reach: a page element's `src`
 * or a scene file can only name a sidecar or a file name, code can also pass the dims.
 */
export const HEADERLESS_RAW_HINT =
  'give its dims and type with a JSON sidecar beside it ({"file": "<name>.raw", "dims": [NX, NY, NZ], "voxel_type": "uint8"}) and load the sidecar (the way for <vpt-viewer src> and scene files), ' +
  'or a file name like name_NXxNYxNZ_uint8.raw, or from code loadVolume(…, { raw: { dims, type } })';

/** Check a raw header given as options or read from a sidecar; anything wrong is 'bad-header' naming the field. */
export function checkRawHeader(raw: Partial<RawHeader> | undefined, name: string, source = 'options.raw'): RawHeader {
  if (!raw || typeof raw !== 'object') {
    throw new RawReadError('bad-header', `${name}: raw data has no header; ${HEADERLESS_RAW_HINT}`);
  }
  // Numbers only: "dims": ["256", …] is a mistake to report, not to convert silently.
  if (Array.isArray(raw.dims) && raw.dims.some((d) => typeof d !== 'number')) {
    throw new RawReadError(
      'bad-header',
      `${name}: ${source} dims ${JSON.stringify(raw.dims)} must be numbers, not strings`,
    );
  }
  const dims = Array.isArray(raw.dims) ? raw.dims.map(Number) : [];
  checkRawDims(dims, name, source);
  if (!RAW_VOXEL_TYPES.includes(raw.type as VoxelType)) {
    throw new RawReadError(
      'bad-header',
      `${name}: ${source} type "${String(raw.type)}" is not one of ${RAW_VOXEL_TYPES.join(', ')}`,
    );
  }
  const spacing =
    raw.spacing === undefined
      ? [1, 1, 1]
      : Array.isArray(raw.spacing) && raw.spacing.every((x) => typeof x === 'number')
        ? raw.spacing.map(Number)
        : [];
  if (spacing.length !== 3 || spacing.some((s) => !Number.isFinite(s) || s <= 0)) {
    throw new RawReadError(
      'bad-header',
      `${name}: ${source} spacing [${String(raw.spacing)}] must be three positive numbers`,
    );
  }
  const endianness = raw.endianness ?? 'little';
  if (endianness !== 'little' && endianness !== 'big') {
    throw new RawReadError(
      'bad-header',
      `${name}: ${source} endianness "${String(endianness)}" must be "little" or "big"`,
    );
  }
  return { dims, type: raw.type as VoxelType, spacing: spacing as [number, number, number], endianness };
}

/** Three letters, one of R/L, A/P and S/I each ("RAS", "PIR"…). */
export function isAxisCodes(s: string): boolean {
  const pairs = s
    .toUpperCase()
    .split('')
    .map((c) => 'RLAPSI'.indexOf(c) >> 1);
  return pairs.length === 3 && pairs.every((p) => p >= 0) && new Set(pairs).size === 3;
}

/** Parse a JSON sidecar of the project's data folder; `name` prefixes every error message. */
export function parseRawSidecar(text: string, name: string): RawSidecar {
  let json: Record<string, unknown>;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw new RawReadError('bad-header', `${name}: the sidecar is not valid JSON (${(e as Error).message})`, {
      cause: e,
    });
  }
  if (!json || typeof json !== 'object' || Array.isArray(json))
    throw new RawReadError('bad-header', `${name}: the sidecar must be a JSON object`);
  if (json.layout !== undefined && typeof json.layout === 'string' && !/x fastest/i.test(json.layout)) {
    throw new RawReadError(
      'unsupported',
      `${name}: layout "${json.layout}" is not supported; vpt reads x-fastest data (index = x + NX·(y + NY·z))`,
    );
  }
  const header = checkRawHeader(
    {
      dims: json.dims as RawHeader['dims'],
      type: (json.voxel_type ?? json.type) as VoxelType,
      spacing: json.spacing as RawHeader['spacing'],
      endianness: json.endianness as RawHeader['endianness'],
    },
    name,
    'sidecar',
  );
  const vr = json.value_range;
  // An inverted range (min > max) is a deliberate inverted mapping; an empty or non-numeric one is a mistake.
  if (
    vr !== undefined &&
    (!Array.isArray(vr) ||
      vr.length !== 2 ||
      !vr.every((x) => typeof x === 'number' && Number.isFinite(x)) ||
      vr[0] === vr[1])
  ) {
    throw new RawReadError(
      'bad-header',
      `${name}: sidecar value_range ${JSON.stringify(vr)} must be two different finite numbers`,
    );
  }
  const meta: Record<string, unknown> = {};
  for (const key of [
    'title',
    'modality',
    'units',
    'spacing_units',
    'orientation',
    'value_range',
    'sha256',
    'license',
    'source',
  ]) {
    if (json[key] !== undefined) meta[key === 'spacing_units' ? 'spacingUnits' : key] = json[key];
  }
  let axisCodes: string | undefined;
  if (json.axes !== undefined) {
    if (typeof json.axes !== 'string' || !isAxisCodes(json.axes)) {
      throw new RawReadError(
        'bad-header',
        `${name}: sidecar axes ${JSON.stringify(json.axes)} must be three letters, one of R/L, A/P and S/I each (like "RAS" or "PIR")`,
      );
    }
    axisCodes = json.axes.toUpperCase();
    meta.axisCodes = axisCodes;
    meta.space = 'RAS';
  }
  const file = typeof json.file === 'string' && json.file ? json.file : undefined;
  return {
    ...header,
    file,
    meta,
    ...(vr ? { valueRange: vr as [number, number] } : {}),
    ...(axisCodes ? { axisCodes } : {}),
  };
}

/**
 * The raw file's URL: the sidecar's `file` when it names one beside the sidecar (no
 * folders), else the sidecar's own base name with .raw.
 */
export function rawFileBeside(sidecarUrl: string, sidecar: { file?: string }): string {
  const file =
    sidecar.file && !/[\\/]/.test(sidecar.file)
      ? sidecar.file
      : sidecarUrl
          .split(/[?#]/)[0]
          .split('/')
          .pop()!
          .replace(/\.json$/i, '') + '.raw';
  return new URL(file, sidecarUrl).href;
}

/** dims and type from a name like `head_256x256x108_int16.raw` (the data folder's pattern). */
export function rawHeaderFromName(name: string): Pick<RawHeader, 'dims' | 'type'> | undefined {
  const m = /(\d+)x(\d+)x(\d+)_(uint8|uint16|int16|float32)\.raw$/i.exec(name);
  return m ? { dims: [Number(m[1]), Number(m[2]), Number(m[3])], type: m[4].toLowerCase() as VoxelType } : undefined;
}

function voxelArrayType(type: VoxelType, name: string) {
  const Ctor = ARRAYS[type];
  if (!Ctor)
    throw new RawReadError('bad-header', `${name}: unknown voxel type "${type}" (${RAW_VOXEL_TYPES.join(', ')})`);
  return Ctor;
}

/**
 * A raw file's size must be exactly dims × type: 'truncated' when short, 'bad-header' when
 * long. Takes only the size, so a caller can check a file from its metadata without reading it.
 */
export function checkRawByteLength(byteLength: number, header: Pick<RawHeader, 'dims' | 'type'>, name: string): void {
  const { dims, type } = header;
  const need = dims[0] * dims[1] * dims[2] * voxelArrayType(type, name).BYTES_PER_ELEMENT;
  if (byteLength !== need) {
    throw new RawReadError(
      byteLength < need ? 'truncated' : 'bad-header',
      `${name}: dims [${dims.join(', ')}] of ${type} need ${need} bytes, the file has ${byteLength}${byteLength > need ? ` (${byteLength - need} bytes past the declared size)` : ''}`,
    );
  }
}

/**
 * The voxels of a raw file: its size must be exactly dims × type (checkRawByteLength);
 * big-endian files are swapped in place (typed arrays use the host's order, little-endian
 * on every platform vpt targets).
 */
export function rawVoxels(
  bytes: Uint8Array,
  header: Pick<RawHeader, 'dims' | 'type'> & { endianness?: 'little' | 'big' },
  name: string,
): VoxelArray {
  const Ctor = voxelArrayType(header.type, name);
  checkRawByteLength(bytes.byteLength, header, name);
  if (header.endianness === 'big' && Ctor.BYTES_PER_ELEMENT > 1) {
    const n = Ctor.BYTES_PER_ELEMENT;
    for (let i = 0; i < bytes.length; i += n) bytes.subarray(i, i + n).reverse();
  }
  // Copy when the bytes are a view at an offset the typed array cannot start at.
  const aligned = bytes.byteOffset % Ctor.BYTES_PER_ELEMENT === 0 ? bytes : bytes.slice();
  return new Ctor(aligned.buffer as ArrayBuffer, aligned.byteOffset, bytes.byteLength / Ctor.BYTES_PER_ELEMENT);
}
