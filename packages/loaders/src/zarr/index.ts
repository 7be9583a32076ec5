/**
 * The OME-Zarr entry points of @vpt/loaders. zarrita and the codecs are imported on first
 * use, so importing @vpt/loaders costs nothing for pages that never read a Zarr store.
 */
import type { MultiscaleSource, OmeZarrOptions } from './multiscale-source.js';

export type { MultiscaleSource, MultiscaleLevel, OmeZarrMeta, OmeZarrOptions } from './multiscale-source.js';
export {
  parseOmeMultiscales,
  type ImageLabelEntry,
  type OmeMultiscale,
  type OmeDataset,
  type OmeAxis,
} from './ome-metadata.js';
export { isZarrLocation, splitZarrLocation, type ZarrSelection } from './location.js';
export {
  writeOmeZarr,
  type WriteOmeZarrOptions,
  type OmeZarrImage,
  type StoreSink,
  type ZarrCodecName,
} from './write-ome-zarr.js';

/**
 * Open an OME-Zarr image (an http(s) URL, or a folder path / file: URL in Node) for reading
 * levels and regions: see MultiscaleSource. Fails with a LoaderError.
 */
export async function openOmeZarr(location: string, options: OmeZarrOptions = {}): Promise<MultiscaleSource> {
  const { openOmeZarr: open } = await import('./multiscale-source.js');
  return open(location, options);
}
