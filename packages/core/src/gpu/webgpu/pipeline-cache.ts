/**
 * Compiled passes for one device: shader module, explicit bind group layout and
 * pipeline layout per distinct generated source, and render pipelines per colour-format
 * list (an offscreen target's formats, or the canvas format). Explicit layouts, not
 * layout: 'auto', because auto layouts drop bindings a kernel variant does not use and
 * the bind group (which always holds every binding) would then fail to match.
 *
 * Compile errors: WebGPU only reports them asynchronously, but createPass() is
 * synchronous. Module and pipeline creation run inside a validation error scope; the
 * scope result and getCompilationInfo() are checked in the background and (a) recorded
 * on the entry, so later createPass()/draw() calls with it throw at once, and (b) handed
 * to DeferredErrors, so the next finish()/readTexture() rejects with the VptError.
 */
import { VptError } from '../../errors.js';
import type { PassDescriptor } from '../backend.js';
import { formatCompileError } from './compile-errors.js';
import type { DeferredErrors } from './deferred-errors.js';
import {
  BUILTINS_BYTE_SIZE,
  FRAGMENT_ENTRY,
  FULLSCREEN_VERTEX_WGSL,
  VERTEX_ENTRY,
  buildWgslSource,
  linearSamplerBinding,
  usesLinearSampler,
} from './wgsl-prelude.js';

export interface PipelineEntry {
  readonly label: string;
  readonly source: string;
  readonly module: GPUShaderModule;
  /** Group 0: the pass's uniforms (binding 0) and textures (bindings 1 + k). */
  readonly bindGroupLayout: GPUBindGroupLayout;
  readonly pipelineLayout: GPUPipelineLayout;
  /** Render pipelines by comma-joined colour formats. */
  readonly pipelines: Map<string, GPURenderPipeline>;
  /** The kernel's compile/link error, once known. */
  error: VptError | null;
  /** Resolves (to `error`) once the verdicts on the module and every pipeline made so far are in. */
  checked: Promise<VptError | null>;
}

export class PipelineCache {
  private readonly entries = new Map<string, PipelineEntry>();
  private readonly vertexModule: GPUShaderModule;
  /** Group 1: the backend-owned VptBuiltins, the same for every pass. */
  readonly builtinsLayout: GPUBindGroupLayout;

  constructor(
    private readonly device: GPUDevice,
    private readonly errors: DeferredErrors,
  ) {
    this.vertexModule = device.createShaderModule({ label: 'vpt full-screen triangle', code: FULLSCREEN_VERTEX_WGSL });
    this.builtinsLayout = device.createBindGroupLayout({
      label: 'vpt builtins',
      entries: [
        {
          binding: 0,
          visibility: GPUShaderStage.FRAGMENT,
          buffer: { type: 'uniform', minBindingSize: BUILTINS_BYTE_SIZE },
        },
      ],
    });
  }

  /**
   * Create the modules of these passes now and their pipelines with createRenderPipelineAsync
   * (the driver compiles them together, off this thread); resolve once all are made. A pipeline
   * the async call refuses is left to the synchronous path, whose error scope reports it.
   */
  async compileAhead(descs: readonly PassDescriptor[]): Promise<void> {
    const made: Promise<unknown>[] = [];
    for (const desc of descs) {
      const key = this.keyOf(desc);
      if (this.entries.has(key)) continue;
      const entry = this.makeEntry(desc, key);
      const formats = desc.outputs.join(',');
      made.push(
        this.device
          .createRenderPipelineAsync(this.pipelineDescriptor(entry, desc.outputs))
          .then((pipeline) => {
            if (!entry.pipelines.has(formats)) entry.pipelines.set(formats, pipeline);
          })
          .catch(() => undefined),
      );
    }
    await Promise.all(made);
  }

  private keyOf(desc: PassDescriptor): string {
    // The source holds the defines, uniform struct, texture declarations and output count;
    // the output formats are the one thing it does not spell out.
    return `${buildWgslSource(desc)}\n// outputs: ${desc.outputs.join(',')}`;
  }

  /** The entry for a descriptor, compiling it on a miss. Throws a compile error already known. */
  get(desc: PassDescriptor): PipelineEntry {
    const key = this.keyOf(desc);
    const hit = this.entries.get(key);
    if (hit) {
      if (hit.error) throw hit.error;
      // Offscreen targets are the common case: their pipeline exists before the first draw.
      this.pipeline(hit, desc.outputs);
      return hit;
    }
    const entry = this.makeEntry(desc, key);
    this.pipeline(entry, desc.outputs);
    return entry;
  }

  /** Module, layouts and compile check of a descriptor, registered under `key`; no pipeline yet. */
  private makeEntry(desc: PassDescriptor, key: string): PipelineEntry {
    const source = buildWgslSource(desc);
    const device = this.device;
    device.pushErrorScope('validation');
    const module = device.createShaderModule({ label: desc.label, code: source });
    const bindGroupLayout = device.createBindGroupLayout({
      label: desc.label,
      entries: [
        {
          binding: 0,
          visibility: GPUShaderStage.FRAGMENT,
          buffer: { type: 'uniform', minBindingSize: desc.uniforms.byteSize },
        },
        // Kernels read with textureLoad, so 'unfilterable-float' admits every format (r32float
        // included); a filtered binding (the volume's fast path) needs a filterable format.
        ...desc.textures.map((t, k): GPUBindGroupLayoutEntry => ({
          binding: 1 + k,
          visibility: GPUShaderStage.FRAGMENT,
          texture: { sampleType: t.filter === 'linear' ? 'float' : 'unfilterable-float', viewDimension: t.dimension },
        })),
        ...(usesLinearSampler(desc)
          ? [
              {
                binding: linearSamplerBinding(desc),
                visibility: GPUShaderStage.FRAGMENT,
                sampler: { type: 'filtering' as const },
              },
            ]
          : []),
      ],
    });
    const pipelineLayout = device.createPipelineLayout({
      label: desc.label,
      bindGroupLayouts: [bindGroupLayout, this.builtinsLayout],
    });
    const scope = device.popErrorScope();

    const entry: PipelineEntry = {
      label: desc.label,
      source,
      module,
      bindGroupLayout,
      pipelineLayout,
      pipelines: new Map(),
      error: null,
      checked: Promise.resolve(null),
    };
    entry.checked = Promise.all([module.getCompilationInfo().catch(() => null), scope.catch(() => null)]).then(
      ([info, scopeError]) => {
        const messages = info?.messages ?? [];
        if (!entry.error && (scopeError || messages.some((m) => m.type === 'error'))) {
          const extra = messages.length === 0 && scopeError ? scopeError.message : undefined;
          entry.error = new VptError('shader-compile', formatCompileError(desc.label, source, messages, extra));
        }
        return entry.error;
      },
    );
    this.errors.track(entry.checked);
    this.entries.set(key, entry);
    return entry;
  }

  private pipelineDescriptor(entry: PipelineEntry, formats: readonly GPUTextureFormat[]): GPURenderPipelineDescriptor {
    return {
      label: `${entry.label} → ${formats.join(',')}`,
      layout: entry.pipelineLayout,
      vertex: { module: this.vertexModule, entryPoint: VERTEX_ENTRY },
      // No blending: passes overwrite every pixel with exact values.
      fragment: { module: entry.module, entryPoint: FRAGMENT_ENTRY, targets: formats.map((format) => ({ format })) },
      primitive: { topology: 'triangle-list' },
    };
  }

  /** The entry's render pipeline for these colour formats, created on first use. */
  pipeline(entry: PipelineEntry, formats: readonly GPUTextureFormat[]): GPURenderPipeline {
    const key = formats.join(',');
    const hit = entry.pipelines.get(key);
    if (hit) return hit;
    const device = this.device;
    device.pushErrorScope('validation');
    const pipeline = device.createRenderPipeline(this.pipelineDescriptor(entry, formats));
    const scope = device.popErrorScope().catch(() => null);
    // Chain onto `checked`, so whoever awaits it (a failed draw) sees this pipeline's verdict too.
    const previous = entry.checked;
    entry.checked = Promise.all([previous, scope]).then(([compileError, err]) => {
      // An invalid module also makes the pipeline invalid: report the compiler's log, not that.
      if (compileError) return compileError;
      if (err && !entry.error) {
        entry.error = new VptError(
          'shader-compile',
          formatCompileError(entry.label, entry.source, [], `render pipeline for [${key}]: ${err.message}`),
        );
      }
      return entry.error;
    });
    this.errors.track(entry.checked);
    entry.pipelines.set(key, pipeline);
    return pipeline;
  }

  /** Forget every entry (device lost or disposed: the objects die with the device). */
  clear(): void {
    this.entries.clear();
  }
}
