/**
 * Three.js' EXRExporter, imported by export.ts on first use so the one-file bundle loads it
 * (and its zlib) only when a page exports an EXR.
 */
import { DataTexture, FloatType, RGBAFormat } from 'three';
import { EXRExporter } from 'three/addons/exporters/EXRExporter.js';

/** Float RGBA rows bottom to top (GL order) as 32-bit float OpenEXR bytes. */
export function writeExr(rgba: Float32Array, width: number, height: number): Promise<Uint8Array> {
  const texture = new DataTexture(rgba, width, height, RGBAFormat, FloatType);
  return new EXRExporter().parse(texture, { type: FloatType });
}
