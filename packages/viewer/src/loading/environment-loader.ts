/**
 * Lat-long HDR environments from a URL: Radiance .hdr (RGBE) and OpenEXR, decoded by
 * Three.js' loaders, converted to core's Environment (RGB floats, row 0 at the top).
 */
import { RequestError, VptError, fetchWithPolicy, type Environment, type RequestPolicy } from '@vpt/core';
import { FloatType } from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import { checkExrHeader, checkHdrHeader, isExr } from './environment-header.js';

interface Decoded {
  width: number;
  height: number;
  data: ArrayLike<number>;
  bottomUp: boolean;
}

/**
 * Decode after the header checks of environment-header.ts (the decoders trust the header:
 * an unbounded loop or allocation otherwise). OpenEXR by its magic number or extension.
 */
function decode(url: string, buffer: ArrayBuffer): Decoded {
  const bytes = new Uint8Array(buffer);
  if (isExr(bytes) || /\.exr(\?|#|$)/i.test(url)) {
    checkExrHeader(bytes, url);
    const r = new EXRLoader().setDataType(FloatType).parse(buffer) as {
      width: number;
      height: number;
      data: Float32Array;
    };
    return { width: r.width, height: r.height, data: r.data, bottomUp: true };
  }
  checkHdrHeader(bytes, url);
  const r = new HDRLoader().setDataType(FloatType).parse(buffer) as {
    width: number;
    height: number;
    data: Float32Array;
  };
  return { width: r.width, height: r.height, data: r.data, bottomUp: false };
}

/** Largest environment file fetched: an 8k × 4k float RGBA EXR, uncompressed. */
export const MAX_ENVIRONMENT_BYTES = 512 * 1024 * 1024;

export interface EnvironmentLoadOptions {
  signal?: AbortSignal;
  /** Bounds on the request (core's RequestPolicy overrides). */
  request?: Partial<RequestPolicy>;
}

export async function loadEnvironment(
  url: string,
  scale = 1,
  options: EnvironmentLoadOptions = {},
): Promise<Environment> {
  const href = new URL(url, globalThis.document?.baseURI).href;
  let buffer: ArrayBuffer;
  try {
    const { bytes } = await fetchWithPolicy(href, {
      signal: options.signal,
      policy: options.request,
      maxBytes: MAX_ENVIRONMENT_BYTES,
    });
    const whole = bytes.byteOffset === 0 && bytes.byteLength === bytes.buffer.byteLength;
    buffer = (whole ? bytes.buffer : bytes.slice().buffer) as ArrayBuffer;
  } catch (e) {
    // A size bound stays limit-exceeded; everything else is a failed load naming the URL.
    const code = e instanceof RequestError ? e.code : 'load-failed';
    throw new VptError(code, `environment: could not fetch ${href} (${(e as Error).message})`, { cause: e });
  }
  let d: Decoded;
  try {
    d = decode(href, buffer);
  } catch (e) {
    if (e instanceof VptError) throw e; // the header checks' own, naming what is wrong
    throw new VptError(
      'load-failed',
      `environment: ${href} is not a readable .hdr/.exr image (${(e as Error).message})`,
      { cause: e },
    );
  }
  const channels = d.data.length / (d.width * d.height);
  if (!d.width || !d.height || !Number.isInteger(channels) || channels < 1)
    throw new VptError('load-failed', `environment: ${href} decoded to an unexpected layout`);
  const rgb = new Float32Array(d.width * d.height * 3);
  for (let row = 0; row < d.height; row++) {
    const srcRow = d.bottomUp ? d.height - 1 - row : row;
    for (let x = 0; x < d.width; x++) {
      const s = (srcRow * d.width + x) * channels;
      const o = (row * d.width + x) * 3;
      for (let c = 0; c < 3; c++) {
        const v = d.data[s + Math.min(c, channels - 1)];
        rgb[o + c] = Number.isFinite(v) && v > 0 ? v : 0;
      }
    }
  }
  return { type: 'latlong', width: d.width, height: d.height, data: rgb, scale };
}
