// Planar reformatting (multiplanar reconstruction): the volume sampled on a plane, windowed in
// data units and colour-mapped. Twin of slice.glsl.ts (same variants, same arithmetic in the same order).

export const generate = /* wgsl */ `
#if COLOR_TABLE
fn colormapLookup(w: f32) -> vec3f {
  let n = i32(textureDimensions(colormap).x);
  let x = w * f32(n - 1);
  let x0 = floor(x);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, n - 1);
  return lerp4(textureLoad(colormap, vec2i(i0, 0), 0), textureLoad(colormap, vec2i(i1, 0), 0), x - x0).rgb;
}
#endif
fn sliceTexel(p: vec3f) -> f32 {
#if NEAREST
  let dims = u.volumeDims.xyz;
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let i = clamp(vec3i(floor(tc * vec3f(dims))), vec3i(0), dims - 1);
  if (u.volumeDims.w == 0) { return textureLoad(volume, i, 0).r; }
  return sampleVolumeTexel(u.boxMin + (vec3f(i) + 0.5) / vec3f(dims) * (u.boxMax - u.boxMin));
#else
  return sampleVolumeTexel(p);
#endif
}
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  let size = vptTargetSize();
#if FIT
  let s = (vec2f(pixel) + 0.5) / vec2f(size);
  let p = u.planeOrigin + u.planeU * s.x + u.planeV * s.y;
  var hit = true;
#else
  let dir = centreCameraRay(pixel, size);
  let denom = dot(dir, u.planeNormal);
  let t = select(-1.0, dot(u.planeOrigin - u.cameraPosition, u.planeNormal) / denom, abs(denom) > 1e-12);
  let p = u.cameraPosition + dir * t;
  var hit = t > 0.0;
#endif
  hit = hit && all(p >= u.boxMin) && all(p <= u.boxMax);
#if VPT_CLIP
  // A clipped part of the plane is cut away like the volume there (the scene's clip planes and box).
  hit = hit && !isClipped(p);
#endif
  var result = vec4f(0.0);
  if (hit) {
    let n = sliceTexel(p) * u.valueScale + u.valueOffset;
    let w = clamp(n * u.windowScale + u.windowOffset, 0.0, 1.0);
#if COLOR_TF
    var rgb = clamp(transferLookup(w).rgb, vec3f(0.0), vec3f(1.0));
#elif COLOR_TABLE
    var rgb = colormapLookup(w);
#else
    var rgb = vec3f(w);
#endif
#if VPT_LABELS
    let l = labelAt(p);
    rgb = rgb + (l.rgb - rgb) * clamp(l.a, 0.0, 1.0);
#endif
    result = vec4f(rgb, 1.0);
  }
  var o: VptOut;
  o.out0 = result;
  return o;
}
`;
