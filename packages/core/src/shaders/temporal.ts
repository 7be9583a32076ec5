import type { KernelSource } from '../renderer.js';
import { UniformLayout } from '../uniforms/layout.js';
import * as glsl from './temporal.glsl.js';
import * as wgsl from './temporal.wgsl.js';

/** The context's temporal-reuse pass (docs/architecture.md, "Temporal reuse"). */
export const TEMPORAL_RESOLVE: KernelSource = { glsl: glsl.TEMPORAL_RESOLVE, wgsl: wgsl.TEMPORAL_RESOLVE };

/** Its uniforms: the new and the old camera (position and basis), the sample counts and the tests' tolerances. */
export const TEMPORAL_UNIFORMS = new UniformLayout('TemporalParams', [
  { name: 'newPosition', type: 'vec3' },
  { name: 'newTanHalfFovy', type: 'f32' },
  { name: 'newForward', type: 'vec3' },
  { name: 'newAspect', type: 'f32' },
  { name: 'newRight', type: 'vec3' },
  { name: 'samples', type: 'u32' },
  { name: 'newUp', type: 'vec3' },
  { name: 'historyScale', type: 'f32' },
  { name: 'oldPosition', type: 'vec3' },
  { name: 'oldTanHalfFovy', type: 'f32' },
  { name: 'oldForward', type: 'vec3' },
  { name: 'oldAspect', type: 'f32' },
  { name: 'oldRight', type: 'vec3' },
  { name: 'maxHistory', type: 'f32' },
  { name: 'oldUp', type: 'vec3' },
  { name: 'depthTolerance', type: 'f32' },
  { name: 'normalCos', type: 'f32' },
  { name: 'historyFilter', type: 'u32' },
  { name: 'footprintWeight', type: 'f32' },
]);
