/**
 * The environment decoder's Web Worker: one request (the URL and the file's bytes), one answer
 * (the decoded image, its buffer transferred, or the error's code and message). Built as a
 * self-contained bundle (rollup.config.mjs) because a module worker gets no import map; the
 * page terminates it after the answer or when the decode passes its time bound.
 */
import { VptError } from '@vpt/core';
import { decodeEnvironment } from './environment-decode.js';

interface Scope {
  onmessage: ((e: MessageEvent<{ url: string; buffer: ArrayBuffer }>) => void) | null;
  postMessage(message: unknown, transfer?: Transferable[]): void;
}
const scope = self as unknown as Scope;

scope.onmessage = (event) => {
  const { url, buffer } = event.data;
  try {
    const d = decodeEnvironment(url, buffer);
    scope.postMessage({ type: 'result', ...d }, [d.data.buffer as ArrayBuffer]);
  } catch (e) {
    const code = e instanceof VptError ? e.code : null;
    scope.postMessage({ type: 'error', code, message: (e as Error)?.message ?? String(e) });
  }
};
