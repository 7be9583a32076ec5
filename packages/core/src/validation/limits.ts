/**
 * What the GPU can represent, and the bounds vpt puts on a scene so that float32 arithmetic
 * in the kernels stays finite and every loop ends. Each limit is named in the VptError a
 * scene breaking it gets.
 */

/** The largest finite float32 (2^128 − 2^104). A number above it becomes Infinity on upload. */
export const FLOAT32_MAX = 3.4028234663852886e38;

/**
 * Largest radiance (environment texel × scale) or irradiance (directional light) accepted.
 * The MCRT and ISO kernels multiply radiance by throughput, MIS weights and inverse pdfs
 * (a lat-long map's pdf reaches ~W·H/(2π² sinθ), up to ~1e7·…) and the environment tables sum
 * luminance × sinθ over up to 2^24 texels; 1e18 keeps every such product, and even its square,
 * below FLOAT32_MAX (1e18² = 1e36), so MIS keeps the energy of the brightest accepted sky.
 */
export const MAX_RADIANCE = 1e18;

/**
 * Largest extinction, densityScale × the transfer function's largest opacity, per world unit
 * (the box's longest side is 1). Free flights are −ln(ξ)/σ long: above ~3e8 they fall below
 * the float32 resolution of a position in the box (~6e-8), paths stop moving until the
 * tracking-step cap ends them, and the MCRT white furnace loses energy (figures:
 * docs/benchmarks.md#fig-limits). densityScale alone has the same bound.
 */
export const MAX_EXTINCTION = 1e8;
export const MAX_DENSITY_SCALE = MAX_EXTINCTION;

/** Largest transfer-function opacity (a multiplier of densityScale; usually ≤ 1). */
export const MAX_OPACITY = 1e6;

/**
 * Largest |coordinate| of the camera position and target. The volume's box has a longest
 * side of 1; at 1e4 a float32 ray parameter still resolves ~1e-3 box units, further out the
 * ray–box intersection degenerates and the volume vanishes.
 */
export const MAX_CAMERA_COORDINATE = 1e4;

/** Most clip planes a scene may have (scene/clip.ts): each is one uniform vec4 and one slab test per ray. */
export const MAX_CLIP_PLANES = 6;

/** Largest |coordinate| of a clip plane's offset and the crop box's corners, as MAX_CAMERA_COORDINATE. */
export const MAX_CLIP_COORDINATE = 1e4;

/** Most samples any ray march takes per ray (EAM, MIP, ISO); the kernels clamp to it. */
export const MAX_MARCH_STEPS = 65536;

/**
 * Smallest ray-march step in voxels of the volume's largest dimension (a step of
 * 0.1 / max(dims) world units): with dims ≤ 2048 a march across the box diagonal then
 * stays below MAX_MARCH_STEPS.
 */
export const MIN_STEP_VOXELS = 0.1;

/** Smallest step size in world units, whatever the volume (the box's longest side is 1). */
export const MIN_STEP_SIZE = 1e-5;

/**
 * Largest side of a procedural test volume: 256³ float32 = 64 MiB, a few seconds to build
 * on a loaded 2-core machine (512³ took over 25 s there, with no progress to show).
 */
export const MAX_PROCEDURAL_SIZE = 256;

/** Largest side of a texture checked before a device is known (WebGPU's default limit). */
export const MAX_TEXTURE_SIDE_2D = 8192;

/** Most directional lights in a scene (MCRT compiles up to 8; ISO uses the first 4). */
export const MAX_SCENE_LIGHTS = 8;

/** Largest render size, iteration count of a headless render. */
export const MAX_RENDER_SIDE = 8192;
export const MAX_ITERATIONS = 1_000_000;
