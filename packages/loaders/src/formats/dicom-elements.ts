/** Reading DICOM element values from a dicom-parser DataSet, a corrupt optional field reading as absent. */

export type DataSet = import('dicom-parser').DataSet;

export const finite = (x: number | undefined): x is number => typeof x === 'number' && Number.isFinite(x);

/**
 * dicom-parser's accessors read element values lazily and can throw on a mangled element
 * (a length past the end, a string VR with no text): a corrupt optional field reads as absent.
 */
export function safe<T>(f: () => T): T | undefined {
  try {
    return f();
  } catch {
    return undefined;
  }
}

export function reader(ds: DataSet) {
  return {
    u16: (tag: string, i?: number) => safe(() => ds.uint16(tag, i)),
    str: (tag: string) => safe(() => ds.string(tag)),
    num: (tag: string, i?: number) => safe(() => ds.floatString(tag, i)),
    int: (tag: string) => safe(() => ds.intString(tag)),
  };
}

/** The raw text of a present element (undefined when absent), for messages. */
export function presentText(ds: DataSet, tag: string): string | undefined {
  const el = (ds as unknown as { elements: Record<string, unknown> }).elements?.[tag];
  if (!el) return undefined;
  const text = safe(() => ds.string(tag));
  return typeof text === 'string' ? text : '';
}

export function numbersOf(ds: DataSet, tag: string, n: number): number[] | undefined {
  const out: number[] = [];
  for (let i = 0; i < n; i++) {
    const v = safe(() => ds.floatString(tag, i));
    if (!finite(v)) return undefined;
    out.push(v);
  }
  return out;
}

/** The data set of a sequence's first item, if the sequence is present and has one. */
export function firstItem(ds: DataSet | undefined, tag: string): DataSet | undefined {
  return ds?.elements[tag]?.items?.[0]?.dataSet;
}
