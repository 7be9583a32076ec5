// Planar reformatting (multiplanar reconstruction, as in any medical image viewer): the volume
// sampled on a plane, windowed in data units and colour-mapped. The same value every iteration
// (no random numbers), so the shared running mean holds it exactly from the first sample.
// Variants: FIT (the plane's rectangle over the image) or the plane under the camera (the
// pixel-centre ray meets the plane); NEAREST (the voxel holding the point) or the shared
// trilinear filter; COLOR_TABLE (the `colormap` texture), COLOR_TF (the 1D transfer function) or grey;
// VPT_LABELS: a scene's label colours laid over it (core's scene/labels.ts).

export const generate = /* glsl */ `
#if COLOR_TABLE
// The colour map's N entries sit at i / (N - 1), linear between them (as transferLookup).
vec3 colormapLookup(float w) {
  int n = textureSize(colormap, 0).x;
  float x = w * float(n - 1);
  float x0 = floor(x);
  int i0 = int(x0);
  int i1 = min(i0 + 1, n - 1);
  return lerp4(texelFetch(colormap, ivec2(i0, 0), 0), texelFetch(colormap, ivec2(i1, 0), 0), x - x0).rgb;
}
#endif
// The texel at a point of the plane, before the value mapping.
float sliceTexel(vec3 p) {
#if NEAREST
  ivec3 dims = u.volumeDims.xyz;
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 i = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
  // u.volumeDims.w is the brick size of a bricked volume, 0 otherwise: the texture is then the voxel grid.
  if (u.volumeDims.w == 0) return texelFetch(volume, i, 0).r;
  // A brick atlas is read through the shared filter, at the voxel's centre.
  return sampleVolumeTexel(u.boxMin + (vec3(i) + 0.5) / vec3(dims) * (u.boxMax - u.boxMin));
#else
  return sampleVolumeTexel(p);
#endif
}
void main() {
  ivec2 pixel = vptPixel();
  ivec2 size = vptTargetSize();
#if FIT
  vec2 s = (vec2(pixel) + 0.5) / vec2(size);
  vec3 p = u.planeOrigin + u.planeU * s.x + u.planeV * s.y;
  bool hit = true;
#else
  vec3 dir = centreCameraRay(pixel, size);
  float denom = dot(dir, u.planeNormal);
  float t = abs(denom) > 1e-12 ? dot(u.planeOrigin - u.cameraPosition, u.planeNormal) / denom : -1.0;
  vec3 p = u.cameraPosition + dir * t;
  bool hit = t > 0.0;
#endif
  hit = hit && all(greaterThanEqual(p, u.boxMin)) && all(lessThanEqual(p, u.boxMax));
#if VPT_CLIP
  // A clipped part of the plane is cut away like the volume there (the scene's clip planes and box).
  hit = hit && !isClipped(p);
#endif
  vec4 result = vec4(0.0);
  if (hit) {
    float n = sliceTexel(p) * u.valueScale + u.valueOffset;
    float w = clamp(n * u.windowScale + u.windowOffset, 0.0, 1.0);
#if COLOR_TF
    vec3 rgb = clamp(transferLookup(w).rgb, vec3(0.0), vec3(1.0));
#elif COLOR_TABLE
    vec3 rgb = colormapLookup(w);
#else
    vec3 rgb = vec3(w);
#endif
#if VPT_LABELS
    // The label of the voxel holding p over the slice, with its opacity (clamped to 1): a segmentation overlay.
    vec4 l = labelAt(p);
    rgb = rgb + (l.rgb - rgb) * clamp(l.a, 0.0, 1.0);
#endif
    result = vec4(rgb, 1.0);
  }
  vpt_out0 = result;
}
`;
