/**
 * Lat-long HDR environments from a URL: Radiance .hdr (RGBE) and OpenEXR, decoded by
 * Three.js' loaders, converted to core's Environment (RGB floats, row 0 at the top).
 */
import { VptError, type Environment } from '@vpt/core';
import { FloatType } from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';

interface Decoded {
  width: number;
  height: number;
  data: ArrayLike<number>;
  bottomUp: boolean;
}

function decode(url: string, buffer: ArrayBuffer): Decoded {
  if (/\.exr(\?|#|$)/i.test(url)) {
    const r = new EXRLoader().setDataType(FloatType).parse(buffer) as {
      width: number;
      height: number;
      data: Float32Array;
    };
    return { width: r.width, height: r.height, data: r.data, bottomUp: true };
  }
  const r = new HDRLoader().setDataType(FloatType).parse(buffer) as {
    width: number;
    height: number;
    data: Float32Array;
  };
  return { width: r.width, height: r.height, data: r.data, bottomUp: false };
}

export async function loadEnvironment(url: string, scale = 1, signal?: AbortSignal): Promise<Environment> {
  const href = new URL(url, globalThis.document?.baseURI).href;
  let buffer: ArrayBuffer;
  try {
    const res = await fetch(href, { signal });
    if (!res.ok) throw new Error(`HTTP ${res.status}`);
    buffer = await res.arrayBuffer();
  } catch (e) {
    throw new VptError('load-failed', `environment: could not fetch ${href} (${(e as Error).message})`, { cause: e });
  }
  let d: Decoded;
  try {
    d = decode(href, buffer);
  } catch (e) {
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
