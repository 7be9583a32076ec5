/**
 * The WebGPURenderer twin of VptCompositor (compositor.ts): the same four steps, with vpt's
 * WebGPU backend on three's own GPUDevice (renderer.backend.device):
 *   1. three's opaque pass into a render target with a depth32float DepthTexture;
 *   2. per volume: vpt's camera rays end at that depth (RenderContext.setDepthLimit with the
 *      GPUTexture), and a raw WebGPU pass on the same device blends the volume's HDR image
 *      over the target (rgb + (1 − a) · target) and, where a ≥ 0.5, writes a representative
 *      depth (the renderer's depth guide, else the box entry);
 *   3. three's transparent pass over it;
 *   4. the target to the canvas (or the given target) through a QuadMesh, which three gives
 *      its tone mapping and output colour space.
 * Everything stays on one device and queue, in submission order: no read-back.
 */
import {
  DepthTexture,
  FloatType,
  HalfFloatType,
  Matrix4,
  MeshBasicNodeMaterial,
  QuadMesh,
  RenderTarget,
  Vector2,
  type Camera,
  type Object3D,
  type Scene,
  type TextureDataType,
  type WebGPURenderer,
} from 'three/webgpu';
import { VptError, volumeBox } from '@vpt/core';
import { VptVolume } from './vpt-volume.js';
import { setVisible, splitMaterials } from './materials.js';

export interface VptWebGPUCompositorOptions {
  /**
   * The colour type of the scene target: HalfFloatType (default: rgba16float, blendable on
   * every device) or FloatType (rgba32float: the device needs 'float32-blendable').
   */
  type?: TextureDataType;
}

// WebGPU's framebuffer rows and vpt's image rows both run top-down, so pixels map as they are;
// clip depth is in [0, 1] (three's WebGPU coordinate system).
const WGSL = /* wgsl */ `
struct U { clipToLocal: mat4x4f, localToClip: mat4x4f, eye: vec4f, boxMin: vec4f, boxMax: vec4f, useGuide: vec4f };
@group(0) @binding(0) var hdr: texture_2d<f32>;
@group(0) @binding(1) var guideDepth: texture_2d<f32>;
@group(0) @binding(2) var guideHit: texture_2d<f32>;
@group(0) @binding(3) var<uniform> u: U;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
  let p = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4f(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fsColour(@builtin(position) fc: vec4f) -> @location(0) vec4f {
  return textureLoad(hdr, vec2i(fc.xy), 0);
}
struct DepthOut { @location(0) c: vec4f, @builtin(frag_depth) depth: f32 };
@fragment fn fsDepth(@builtin(position) fc: vec4f) -> DepthOut {
  let q = vec2i(fc.xy);
  let c = textureLoad(hdr, q, 0);
  if (c.a < 0.5) { discard; }
  let size = vec2f(textureDimensions(hdr));
  let ndc = vec2f(fc.x / size.x * 2.0 - 1.0, 1.0 - fc.y / size.y * 2.0);
  let f = u.clipToLocal * vec4f(ndc, 1.0, 1.0);
  let eye = u.eye.xyz;
  let dir = normalize(f.xyz / f.w - eye);
  var t: f32;
  if (u.useGuide.x > 0.5) {
    let hit = textureLoad(guideHit, q, 0).a;
    if (!(hit > 0.0)) { discard; }
    t = textureLoad(guideDepth, q, 0).a / hit;
  } else {
    let inv = 1.0 / dir;
    let t0 = (u.boxMin.xyz - eye) * inv;
    let t1 = (u.boxMax.xyz - eye) * inv;
    let tmin = min(t0, t1);
    let tmax = max(t0, t1);
    t = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
    if (t >= min(min(tmax.x, tmax.y), tmax.z)) { discard; }
  }
  let clip = u.localToClip * vec4f(eye + dir * t, 1.0);
  return DepthOut(c, clamp(clip.z / clip.w, 0.0, 1.0));
}`;

interface Pipelines {
  colour: GPURenderPipeline;
  depth: GPURenderPipeline;
  uniforms: GPUBuffer;
  format: GPUTextureFormat;
}

type BackendInternals = { device: GPUDevice | null; get(o: object): { texture?: GPUTexture } };

export class VptWebGPUCompositor {
  /** The scene target: linear colour (HalfFloat or Float) and a depth32float depth texture. */
  readonly target: RenderTarget;
  private pipelines: Pipelines | null = null;
  private readonly quad: QuadMesh;
  private readonly output: MeshBasicNodeMaterial;

  constructor(
    readonly renderer: WebGPURenderer,
    options: VptWebGPUCompositorOptions = {},
  ) {
    const size = renderer.getDrawingBufferSize(new Vector2());
    this.target = new RenderTarget(size.x, size.y, {
      type: options.type ?? HalfFloatType,
      depthTexture: new DepthTexture(size.x, size.y, FloatType),
      depthBuffer: true,
    });
    this.output = new MeshBasicNodeMaterial({ map: this.target.texture, depthTest: false, depthWrite: false });
    this.quad = new QuadMesh(this.output);
  }

  /** The GPUDevice of the renderer (after `await renderer.init()`); VptError when it is not WebGPU. */
  get device(): GPUDevice {
    const backend = (this.renderer as unknown as { backend: BackendInternals & { isWebGPUBackend?: boolean } }).backend;
    if (!backend.isWebGPUBackend || !backend.device)
      throw new VptError(
        'no-backend',
        'VptWebGPUCompositor needs a WebGPURenderer on its WebGPU backend, initialised (await renderer.init()); ' +
          'its WebGL 2 fallback is not supported (use VptCompositor with a WebGLRenderer)',
      );
    return backend.device;
  }

  volumesOf(scene: Object3D): VptVolume[] {
    const out: VptVolume[] = [];
    scene.traverseVisible((o) => {
      if (o instanceof VptVolume) out.push(o);
    });
    return out;
  }

  /** Make the vpt contexts of the scene's volumes on the renderer's device (initialises the renderer first). */
  async prepare(scene: Object3D): Promise<void> {
    // init() throws when called twice; three keeps whether it ran in `_initialized`.
    if (!(this.renderer as unknown as { _initialized: boolean })._initialized) await this.renderer.init();
    const size = this.renderer.getDrawingBufferSize(new Vector2());
    const device = this.device;
    await Promise.all(this.volumesOf(scene).map((v) => v.connectDevice(device, size.x, size.y)));
  }

  /** Draw `scene` as seen by `camera` into `output` (default: the canvas), after drawing it into `target`. */
  render(scene: Scene, camera: Camera, output: RenderTarget | null = null): void {
    const r = this.renderer;
    const device = this.device;
    const size = r.getDrawingBufferSize(new Vector2());
    if (this.target.width !== size.x || this.target.height !== size.y) this.target.setSize(size.x, size.y);
    scene.updateMatrixWorld();
    if (camera.parent === null) camera.updateMatrixWorld();
    const volumes = this.volumesOf(scene);
    const { opaque, transparent } = splitMaterials(scene);
    const autoClear = r.autoClear;
    const background = scene.background;
    // 1. The opaque pass (three submits it before returning).
    setVisible(transparent, false);
    r.setRenderTarget(this.target);
    r.render(scene, camera);
    setVisible(transparent, true);
    // 2. The volumes, on the same device and queue.
    const backend = (r as unknown as { backend: BackendInternals }).backend;
    const depth = backend.get(this.target.depthTexture!).texture ?? null;
    const colour = backend.get(this.target.texture).texture ?? null;
    for (const v of volumes) {
      if (!v.context) {
        void v.connectDevice(device, size.x, size.y);
        continue;
      }
      const hdr = v.refineDevice(camera, size.x, size.y, depth);
      if (hdr && colour && depth && v.lastView) this.composite(device, hdr, colour, depth, camera, v);
    }
    // 3. The transparent pass over it.
    if (transparent.length > 0) {
      setVisible(opaque, false);
      scene.background = null;
      r.autoClear = false;
      r.setRenderTarget(this.target);
      r.render(scene, camera);
      r.autoClear = autoClear;
      scene.background = background;
      setVisible(opaque, true);
    }
    // 4. Output.
    r.setRenderTarget(output);
    this.quad.render(r);
  }

  private composite(
    device: GPUDevice,
    hdr: GPUTexture,
    colour: GPUTexture,
    depth: GPUTexture,
    camera: Camera,
    v: VptVolume,
  ): void {
    const p = this.pipelinesFor(device, colour.format);
    const view = v.lastView!;
    const localToClip = new Matrix4()
      .multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse)
      .multiply(view.toWorld);
    const clipToLocal = localToClip.clone().invert();
    const box = volumeBox(view.scene.volume);
    const guide = v.context?.depthGuideGpuTextures() ?? null;
    const u = new Float32Array(48);
    u.set(clipToLocal.elements, 0);
    u.set(localToClip.elements, 16);
    u.set(view.scene.camera.position, 32);
    u.set(box.min, 36);
    u.set(box.max, 40);
    u[44] = guide ? 1 : 0;
    device.queue.writeBuffer(p.uniforms, 0, u);
    const bind = (pipeline: GPURenderPipeline) =>
      device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [
          { binding: 0, resource: hdr.createView() },
          { binding: 1, resource: (guide?.normalDepth ?? hdr).createView() },
          { binding: 2, resource: (guide?.albedoHit ?? hdr).createView() },
          { binding: 3, resource: { buffer: p.uniforms } },
        ],
      });
    const encoder = device.createCommandEncoder({ label: 'vpt three composite' });
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: colour.createView(), loadOp: 'load', storeOp: 'store' }],
      depthStencilAttachment: { view: depth.createView(), depthLoadOp: 'load', depthStoreOp: 'store' },
    });
    pass.setPipeline(p.colour);
    pass.setBindGroup(0, bind(p.colour));
    pass.draw(3);
    pass.setPipeline(p.depth);
    pass.setBindGroup(0, bind(p.depth));
    pass.draw(3);
    pass.end();
    device.queue.submit([encoder.finish()]);
  }

  private pipelinesFor(device: GPUDevice, format: GPUTextureFormat): Pipelines {
    if (this.pipelines?.format === format) return this.pipelines;
    this.pipelines?.uniforms.destroy();
    const module = device.createShaderModule({ label: 'vpt three composite', code: WGSL });
    const layout = device.createBindGroupLayout({
      entries: [
        ...[0, 1, 2].map((binding): GPUBindGroupLayoutEntry => ({
          binding,
          visibility: GPUShaderStage.FRAGMENT,
          texture: { sampleType: 'unfilterable-float' },
        })),
        { binding: 3, visibility: GPUShaderStage.FRAGMENT, buffer: { type: 'uniform' } },
      ],
    });
    const pipelineLayout = device.createPipelineLayout({ bindGroupLayouts: [layout] });
    const make = (entryPoint: string, blend: boolean): GPURenderPipeline =>
      device.createRenderPipeline({
        layout: pipelineLayout,
        vertex: { module, entryPoint: 'vs' },
        fragment: {
          module,
          entryPoint,
          targets: [
            blend
              ? {
                  format,
                  // rgb + (1 − a) · what is there (vpt's rgb is radiance, not multiplied by a).
                  blend: {
                    color: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha', operation: 'add' },
                    alpha: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha', operation: 'add' },
                  },
                }
              : { format, writeMask: 0 },
          ],
        },
        primitive: { topology: 'triangle-list' },
        depthStencil: blend
          ? { format: 'depth32float', depthWriteEnabled: false, depthCompare: 'always' }
          : { format: 'depth32float', depthWriteEnabled: true, depthCompare: 'less' },
      });
    this.pipelines = {
      colour: make('fsColour', true),
      depth: make('fsDepth', false),
      uniforms: device.createBuffer({ size: 48 * 4, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST }),
      format,
    };
    return this.pipelines;
  }

  dispose(): void {
    this.target.dispose();
    this.output.dispose();
    this.pipelines?.uniforms.destroy();
    this.pipelines = null;
  }
}
