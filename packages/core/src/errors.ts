/**
 * Every failure vpt reports is a VptError with a machine-readable `code`, so an
 * application can branch on the kind of failure and show `message` to a person.
 */
export type VptErrorCode =
  | 'invalid-scene' // a scene object that breaks the model's rules (NaN camera, empty volume…)
  | 'limit-exceeded' // the scene needs more than the device offers (3D texture size…)
  | 'no-backend' // neither WebGPU nor WebGL 2 is available
  | 'missing-extension' // WebGL 2 without EXT_color_buffer_float, WebGPU without a feature
  | 'shader-compile' // a kernel failed to compile or link (a bug in vpt, reported with the log)
  | 'context-lost' // the GPU context was lost and could not be restored
  | 'disposed' // the context was used after dispose()
  | 'load-failed'; // a file could not be fetched or parsed

export class VptError extends Error {
  readonly code: VptErrorCode;
  constructor(code: VptErrorCode, message: string, options?: { cause?: unknown }) {
    super(message, options);
    this.name = 'VptError';
    this.code = code;
  }
}

export function isVptError(e: unknown, code?: VptErrorCode): e is VptError {
  return e instanceof VptError && (code === undefined || e.code === code);
}
