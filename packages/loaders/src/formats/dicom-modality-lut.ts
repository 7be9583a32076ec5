/**
 * The Modality LUT Sequence (0028,3000; PS3.3 C.11.1): stored values mapped through a
 * table to output units, in place of Rescale Slope/Intercept. Values below the first
 * mapped one take the first entry, values past the table the last (PS3.3 C.11.1.1).
 */
import { LoaderError } from '../errors.js';
import { firstItem, type DataSet } from './dicom-elements.js';

export interface ModalityLut {
  /** The stored value that maps to entry 0. */
  first: number;
  /** The table, one 16-bit word per entry (8-bit tables keep their low byte). */
  table: Uint16Array | Uint8Array;
  bits: 8 | 16;
}

/** The file's Modality LUT, or undefined when it has none. */
export function readModalityLut(
  ds: DataSet,
  little: boolean,
  signedPixels: boolean,
  where: string,
): ModalityLut | undefined {
  const item = firstItem(ds, 'x00283000');
  if (!item) return undefined;
  const desc = item.elements.x00283002;
  const data = item.elements.x00283006;
  if (!desc || desc.length < 6 || !data)
    throw new LoaderError('bad-header', `${where}: the Modality LUT Sequence lacks its LUT Descriptor or LUT Data`);
  const bytes = item.byteArray as Uint8Array;
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const word = (at: number) => view.getUint16(at, little);
  const entries = word(desc.dataOffset) || 65536; // 0 means 2^16 entries
  const firstRaw = word(desc.dataOffset + 2);
  // The first mapped value is US, or SS when the pixels are signed (PS3.3 C.11.1.1.1).
  const first = signedPixels && firstRaw >= 0x8000 ? firstRaw - 0x10000 : firstRaw;
  const bitsRaw = word(desc.dataOffset + 4);
  if (bitsRaw !== 8 && bitsRaw !== 16)
    throw new LoaderError('unsupported', `${where}: a Modality LUT of ${bitsRaw}-bit entries (8 or 16 are read)`);
  if (data.length < entries * 2 || data.dataOffset + entries * 2 > bytes.length)
    throw new LoaderError(
      'truncated',
      `${where}: the Modality LUT Data holds ${data.length} bytes; its descriptor announces ${entries} 16-bit entries`,
    );
  const table = bitsRaw === 8 ? new Uint8Array(entries) : new Uint16Array(entries);
  for (let i = 0; i < entries; i++) table[i] = word(data.dataOffset + 2 * i) & (bitsRaw === 8 ? 0xff : 0xffff);
  return { first, table, bits: bitsRaw };
}

/** The stored values of one frame mapped through the LUT. */
export function applyModalityLut(values: ArrayLike<number>, lut: ModalityLut): Uint16Array | Uint8Array {
  const out = lut.bits === 8 ? new Uint8Array(values.length) : new Uint16Array(values.length);
  const last = lut.table.length - 1;
  for (let i = 0; i < values.length; i++) {
    const k = values[i] - lut.first;
    out[i] = lut.table[k < 0 ? 0 : k > last ? last : k];
  }
  return out;
}
