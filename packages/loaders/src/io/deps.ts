import { LoaderError } from '../errors.js';

/**
 * Load an npm parser on demand, so a raw load never pays for the DICOM parser. In a page
 * without a bundler or an import map for these names the import fails; say what to do.
 */
export async function loadDependency<T>(name: string, load: () => Promise<T>): Promise<T> {
  try {
    return await load();
  } catch (e) {
    throw new LoaderError(
      'unsupported',
      `Could not load the parser module "${name}" (${(e as Error)?.message ?? e}). ` +
        'Use a bundler, or load through the worker (dist/worker/), which has its parsers built in',
      { cause: e },
    );
  }
}

export const fflate = () => loadDependency('fflate', () => import('fflate'));
