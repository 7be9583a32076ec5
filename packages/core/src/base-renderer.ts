import type { TextureFormat } from './gpu/backend.js';
import type { KernelSource, Renderer } from './renderer.js';
import type { Scene } from './scene/scene.js';
import type { UniformField, UniformValues } from './uniforms/layout.js';
import { validateParams, type ParamSpecs } from './validation/params.js';

/**
 * What every renderer plugin shares: parameters kept as a plain object, and a version
 * bumped on every change so the RenderContext knows to reset accumulation.
 * Subclasses declare kernels, formats and parameter fields.
 */
export abstract class BaseRenderer<P extends object> implements Renderer {
  abstract readonly name: string;
  abstract readonly frameFormats: readonly TextureFormat[];
  abstract readonly accumulationFormats: readonly TextureFormat[];
  abstract readonly kernels: {
    readonly generate: KernelSource;
    readonly integrate: KernelSource;
    readonly render: KernelSource;
  };
  abstract readonly paramFields: readonly UniformField[];
  private _version = 0;
  private params: P;
  readonly paramSpecs?: ParamSpecs;

  /**
   * With `specs`, the parameters are validated here and on every setParams (unknown keys,
   * ranges, float32): a bad value throws VptError('invalid-scene') naming `<name>.<key>`.
   */
  constructor(params: P, specs?: ParamSpecs, owner?: string) {
    if (specs) validateParams(owner ?? 'renderer', specs, params ?? {});
    this.params = { ...params };
    this.paramSpecs = specs;
    this.owner = owner ?? 'renderer';
  }

  private readonly owner: string;

  get version(): number {
    return this._version;
  }

  /** Merge new parameter values; the next iteration starts a new accumulation. */
  setParams(params: Partial<P>): void {
    if (this.paramSpecs) validateParams(this.owner, this.paramSpecs, { ...this.params, ...params });
    this.params = { ...this.params, ...params };
    this._version++;
  }

  getParams(): P {
    return { ...this.params };
  }

  abstract paramValues(scene: Scene): UniformValues;

  features(_scene: Scene): Record<string, boolean | number> {
    return {};
  }
}
