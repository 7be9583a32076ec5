import type { KernelSource } from '../renderer.js';
import * as glsl from './guides.glsl.js';
import * as wgsl from './guides.wgsl.js';

/** Generate-pass helpers guideNormalDepth(p, t) / guideAlbedo(rgb), included when VPT_GUIDES is on. */
export const GUIDES: KernelSource = { glsl: glsl.GUIDES, wgsl: wgsl.GUIDES };

/** The context's guide integrate pass: running means of the guides and of the luminance moments. */
export const GUIDE_INTEGRATE: KernelSource = { glsl: glsl.GUIDE_INTEGRATE, wgsl: wgsl.GUIDE_INTEGRATE };
