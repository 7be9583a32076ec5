/**
 * The request policy of a headless render (core's RequestPolicy: the bounds every URL a
 * scene names is fetched under) from the environment: `VPT_REQUEST_POLICY` holds JSON
 * overrides, e.g. `{"stallTimeoutMs": 2000, "totalTimeoutMs": 20000}`, checked here so a
 * bad value fails before a browser starts.
 */
import { resolveRequestPolicy, VptError, type RequestPolicy } from '@vpt/core';

export const REQUEST_POLICY_ENV = 'VPT_REQUEST_POLICY';

export function requestPolicyFromEnv(env: NodeJS.ProcessEnv = process.env): Partial<RequestPolicy> {
  const text = env[REQUEST_POLICY_ENV];
  if (text === undefined || text.trim() === '') return {};
  let parsed: unknown;
  try {
    parsed = JSON.parse(text);
  } catch (e) {
    throw new VptError('invalid-scene', `${REQUEST_POLICY_ENV}: not valid JSON (${(e as Error).message})`);
  }
  try {
    resolveRequestPolicy(parsed as Partial<RequestPolicy>);
  } catch (e) {
    throw new VptError('invalid-scene', `${REQUEST_POLICY_ENV}: ${(e as Error).message}`);
  }
  return parsed as Partial<RequestPolicy>;
}
