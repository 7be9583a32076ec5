/**
 * The decode of an environment file's bytes (Radiance .hdr and OpenEXR, by Three.js' loaders),
 * after the header checks of environment-header.ts (the decoders trust the header: an
 * unbounded loop or allocation otherwise). Runs in environment-worker.ts, so a decoder that
 * still loops or takes long on a hostile file can be stopped without freezing the page.
 */
import { FloatType } from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import { checkExrHeader, checkHdrHeader, isExr } from './environment-header.js';

export interface DecodedEnvironment {
  width: number;
  height: number;
  data: Float32Array;
  bottomUp: boolean;
}

/** OpenEXR by its magic number or extension, else Radiance .hdr. */
export function decodeEnvironment(url: string, buffer: ArrayBuffer): DecodedEnvironment {
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
