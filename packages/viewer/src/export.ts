/**
 * Image export: the displayed (LDR) image as PNG, the linear HDR render as PFM or as
 * a 32-bit float OpenEXR (Three.js' EXRExporter). Inputs are vpt read-backs: RGBA,
 * top row first.
 */

/** PNG of an RGBA8 image (alpha forced to opaque: a screenshot shows what is on screen). */
export async function encodePngBlob(rgba: Uint8Array, width: number, height: number): Promise<Blob> {
  const pixels = new Uint8ClampedArray(rgba.length);
  pixels.set(rgba);
  for (let i = 3; i < pixels.length; i += 4) pixels[i] = 255;
  const image = new ImageData(pixels, width, height);
  if (typeof OffscreenCanvas !== 'undefined') {
    const canvas = new OffscreenCanvas(width, height);
    canvas.getContext('2d')!.putImageData(image, 0, 0);
    return canvas.convertToBlob({ type: 'image/png' });
  }
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  canvas.getContext('2d')!.putImageData(image, 0, 0);
  return new Promise((resolve, reject) =>
    canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('PNG encoding failed'))), 'image/png'),
  );
}

/** Portable float map (colour "PF", little-endian, rows bottom to top as the format requires). */
export function encodePfm(rgba: Float32Array, width: number, height: number): Uint8Array {
  const header = new TextEncoder().encode(`PF\n${width} ${height}\n-1.0\n`);
  const out = new Uint8Array(header.length + width * height * 12);
  out.set(header);
  const view = new DataView(out.buffer, header.length);
  let o = 0;
  for (let row = height - 1; row >= 0; row--) {
    for (let x = 0; x < width; x++) {
      const i = (row * width + x) * 4;
      for (let c = 0; c < 3; c++, o += 4) view.setFloat32(o, finite(rgba[i + c]), true);
    }
  }
  return out;
}

/** OpenEXR, RGBA 32-bit float, ZIP-compressed. */
export async function encodeExr(rgba: Float32Array, width: number, height: number): Promise<Uint8Array> {
  // EXRExporter expects GL's bottom-to-top rows.
  const flipped = new Float32Array(rgba.length);
  for (let row = 0; row < height; row++) {
    const src = rgba.subarray(row * width * 4, (row + 1) * width * 4);
    flipped.set(src, (height - 1 - row) * width * 4);
  }
  for (let i = 0; i < flipped.length; i++) flipped[i] = finite(flipped[i]);
  // Loaded on first use (a lazy chunk of the one-file bundle): most pages never export EXR.
  // (Named imports in a module of ours: import('three') itself would keep all of Three.js.)
  const { writeExr } = await import('./export-exr.js');
  return writeExr(flipped, width, height);
}

function finite(x: number): number {
  return Number.isFinite(x) ? x : 0;
}

/** Offer bytes as a download named `filename`. */
export function download(data: Blob | Uint8Array, filename: string, type = 'application/octet-stream'): void {
  const blob = data instanceof Blob ? data : new Blob([data as Uint8Array<ArrayBuffer>], { type });
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = filename;
  a.style.display = 'none';
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
