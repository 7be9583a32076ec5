/**
 * The shared Node-side test scene (unit tests of core and the renderers): a small blob under
 * a white sky, the ramp transfer function, the default camera, no lights. Tests override
 * what they exercise. (The in-page twin is `window.t.scene()` in in-page.ts.)
 */
import {
  createProceduralVolume,
  defaultCamera,
  isVptError,
  rampTransferFunction,
  type Scene,
  type TransferFunction,
  type Vec3,
  type VptErrorCode,
} from '@vpt/core';

/** One stop of a test's 1D transfer function: [value, color, opacity]. */
export type TfStop = [value: number, color: Vec3, opacity: number];

/** A 1D transfer function from compact stops, so tests state their TF in a line or two. (In-page twin: `window.t.tf1d()`.) */
export function tf1d(...stops: TfStop[]): TransferFunction {
  return { dimensions: '1d', points: stops.map(([value, color, opacity]) => ({ value, color, opacity })) };
}

export function testScene(overrides: Partial<Scene> = {}): Scene {
  return {
    volume: createProceduralVolume('blob', 8),
    transferFunction: rampTransferFunction(),
    camera: defaultCamera(),
    lights: [],
    environment: { type: 'constant', radiance: [1, 1, 1] },
    densityScale: 1,
    seed: 0,
    ...overrides,
  };
}

/** Run `fn` and expect a VptError with `code` whose message matches `pattern`. */
export function expectVptError(fn: () => unknown, code: VptErrorCode, pattern: RegExp): void {
  let error: unknown;
  try {
    fn();
  } catch (e) {
    error = e;
  }
  if (error === undefined) throw new Error(`expected a VptError ('${code}') matching ${pattern}`);
  if (!isVptError(error) || error.code !== code)
    throw new Error(`expected a VptError ('${code}'), got ${String(error)}`);
  if (!pattern.test((error as Error).message))
    throw new Error(`expected the message to match ${pattern}, got "${(error as Error).message}"`);
}

/** The VptError `fn` throws, as its code and message; fails when it throws nothing or something else. */
export function thrownVptError(fn: () => unknown): { code: VptErrorCode; message: string } {
  try {
    fn();
  } catch (e) {
    if (!isVptError(e)) throw new Error(`expected a VptError, got ${String(e)}`);
    return { code: e.code, message: (e as Error).message };
  }
  throw new Error('expected a VptError, nothing was thrown');
}
