import { volumeBox, type Camera, type Volume } from '@vpt/core';
import { DEFAULT_FOVY } from './attributes.js';

/** Direction the default camera looks from: front-right, a little above (y up). */
const DEFAULT_DIRECTION = [0.55, 0.35, 1];

/** A camera that frames the whole volume box (its bounding sphere fits the vertical field of view). */
export function fitCamera(volume: Pick<Volume, 'dims' | 'spacing'>, fovy = DEFAULT_FOVY): Camera {
  const { size } = volumeBox(volume);
  const radius = Math.hypot(size[0], size[1], size[2]) / 2;
  const distance = (1.05 * radius) / Math.sin(fovy / 2);
  const len = Math.hypot(DEFAULT_DIRECTION[0], DEFAULT_DIRECTION[1], DEFAULT_DIRECTION[2]);
  const position = DEFAULT_DIRECTION.map((d) => Math.round((d / len) * distance * 1e6) / 1e6) as Camera['position'];
  return { position, target: [0, 0, 0], up: [0, 1, 0], fovy };
}
