// Running means of all, even and odd iterations. Twin of accumulate.glsl.ts.

export const integrate = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f = textureLoad(frame0, p, 0);
  let n = u.iteration;
  var r: VptOut;
  if (n == 0u) { r.out0 = f; r.out1 = f; r.out2 = vec4f(0.0); return r; }
  let a = textureLoad(accum0, p, 0);
  let e = textureLoad(accum1, p, 0);
  let o = textureLoad(accum2, p, 0);
  r.out0 = a + (f - a) * (1.0 / f32(n + 1u));
  let wHalf = 1.0 / f32(n / 2u + 1u);
  if ((n & 1u) == 0u) {
    r.out1 = e + (f - e) * wHalf;
    r.out2 = o;
  } else {
    r.out1 = e;
    r.out2 = o + (f - o) * wHalf;
  }
  return r;
}
`;
