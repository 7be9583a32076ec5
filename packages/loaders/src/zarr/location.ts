/**
 * How an OME-Zarr store is named: a URL or path ending in `.zarr` (`.ome.zarr`), with an
 * optional fragment choosing what to read, `#level=2&channel=1&time=0`. The fragment is
 * never sent to a server, so one string (a viewer's `src`, a gallery link) says it all.
 */
import { LoaderError } from '../errors.js';

export interface ZarrSelection {
  /** Level index (0 = finest), or 'coarsest'. */
  level?: number | 'coarsest';
  channel?: number;
  time?: number;
}

/** Does this URL or path name a Zarr store (…/x.zarr or …/x.ome.zarr, a trailing slash, query or fragment allowed)? */
export function isZarrLocation(location: string): boolean {
  return /\.zarr\/?([?#].*)?$/i.test(location);
}

/** The location without its fragment, and the selection the fragment makes. */
export function splitZarrLocation(location: string): { store: string; selection: ZarrSelection } {
  const hash = location.indexOf('#');
  if (hash < 0) return { store: location, selection: {} };
  const store = location.slice(0, hash);
  const selection: ZarrSelection = {};
  for (const [key, value] of new URLSearchParams(location.slice(hash + 1))) {
    if (key === 'level' && value === 'coarsest') selection.level = 'coarsest';
    else if (key === 'level' || key === 'channel' || key === 'time') {
      const n = Number(value);
      if (!/^\d+$/.test(value) || !Number.isSafeInteger(n))
        throw new LoaderError(
          'bad-header',
          `${location}: "${key}=${value}" in the fragment must be a non-negative integer`,
        );
      selection[key] = n;
    } else {
      throw new LoaderError('bad-header', `${location}: unknown fragment key "${key}" (level, channel, time)`);
    }
  }
  return { store, selection };
}
