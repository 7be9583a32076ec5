/**
 * Draws a three.js scene with its VptVolumes, depth-correctly:
 *   1. three's opaque pass into a render target with a depth texture;
 *   2. per volume: vpt's camera rays end at that depth (RenderContext.setDepthLimit), the
 *      volume's HDR image (radiance, a = 1 − transmittance) is composited over the target,
 *      rgb + (1 − a) · target, and where a ≥ 0.5 a representative depth (the renderer's depth
 *      guide, else the box entry) is written, so what is drawn later behind an opaque part of
 *      the volume is hidden and what is in front of the medium shows;
 *   3. three's transparent pass over it, as three.js orders them;
 *   4. the target to the canvas (or the given target) with three's tone mapping and output
 *      colour space.
 * Everything stays on the renderer's WebGL 2 context: no read-back.
 */
import {
  DepthTexture,
  FloatType,
  HalfFloatType,
  Matrix4,
  Mesh,
  OrthographicCamera,
  PlaneGeometry,
  ShaderMaterial,
  Vector2,
  WebGLRenderTarget,
  type Camera,
  type Object3D,
  type Scene,
  type TextureDataType,
  type WebGLRenderer,
} from 'three';
import { volumeBox } from '@vpt/core';
import { VptVolume } from './vpt-volume.js';
import { setVisible, splitMaterials } from './materials.js';

export interface VptCompositorOptions {
  /** The colour type of the scene target: HalfFloatType (default) or FloatType. */
  type?: TextureDataType;
}

const VERTEX = `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

// vpt's image rows run top-down (vptPixel), GL's bottom-up.
const COLOUR = `#version 300 es
precision highp float;
uniform highp sampler2D hdr;
out vec4 o;
void main() {
  ivec2 size = textureSize(hdr, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  o = texelFetch(hdr, ivec2(p.x, size.y - 1 - p.y), 0);
}`;

// Where the volume is at least half opaque, the depth of the point that stands for the pixel:
// the renderer's accumulated depth guide (mean distance of its hits along the ray: MCRT's first
// real collisions, EAM's mean termination depth, ISO's surface), or the box entry for a renderer
// without guides (MIP).
const DEPTH = `#version 300 es
precision highp float;
uniform highp sampler2D hdr;
uniform highp sampler2D guideDepth;
uniform highp sampler2D guideHit;
uniform bool useGuide;
uniform mat4 clipToLocal;
uniform mat4 localToClip;
uniform vec3 eye;
uniform vec3 boxMin;
uniform vec3 boxMax;
out vec4 o;
void main() {
  ivec2 size = textureSize(hdr, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 q = ivec2(p.x, size.y - 1 - p.y);
  vec4 c = texelFetch(hdr, q, 0);
  if (c.a < 0.5) discard;
  vec2 ndc = gl_FragCoord.xy / vec2(size) * 2.0 - 1.0;
  vec4 f = clipToLocal * vec4(ndc, 1.0, 1.0);
  vec3 dir = normalize(f.xyz / f.w - eye);
  float t;
  if (useGuide) {
    float hit = texelFetch(guideHit, q, 0).a;
    if (!(hit > 0.0)) discard;
    t = texelFetch(guideDepth, q, 0).a / hit;
  } else {
    vec3 inv = 1.0 / dir;
    vec3 t0 = (boxMin - eye) * inv;
    vec3 t1 = (boxMax - eye) * inv;
    vec3 tmin = min(t0, t1);
    vec3 tmax = max(t0, t1);
    t = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
    if (t >= min(min(tmax.x, tmax.y), tmax.z)) discard;
  }
  vec4 clip = localToClip * vec4(eye + dir * t, 1.0);
  gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
  o = c;
}`;

interface Programs {
  colour: WebGLProgram;
  depth: WebGLProgram;
  vao: WebGLVertexArrayObject;
}

function program(gl: WebGL2RenderingContext, fs: string): WebGLProgram {
  const p = gl.createProgram()!;
  for (const [type, src] of [
    [gl.VERTEX_SHADER, VERTEX],
    [gl.FRAGMENT_SHADER, fs],
  ] as const) {
    const sh = gl.createShader(type)!;
    gl.shaderSource(sh, src);
    gl.compileShader(sh);
    if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error(`@vpt/three: ${gl.getShaderInfoLog(sh)}`);
    gl.attachShader(p, sh);
    gl.deleteShader(sh);
  }
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(`@vpt/three: ${gl.getProgramInfoLog(p)}`);
  return p;
}

type Internals = { get(o: object): { __webglFramebuffer?: WebGLFramebuffer; __webglTexture?: WebGLTexture } };

export class VptCompositor {
  /** The scene target: linear colour (HalfFloat or Float) and a float depth texture. */
  readonly target: WebGLRenderTarget;
  private programs: Programs | null = null;
  private readonly quad: Mesh;
  private readonly quadCamera = new OrthographicCamera(-1, 1, 1, -1, 0, 1);
  private readonly output: ShaderMaterial;

  constructor(
    readonly renderer: WebGLRenderer,
    options: VptCompositorOptions = {},
  ) {
    const size = renderer.getDrawingBufferSize(new Vector2());
    this.target = new WebGLRenderTarget(size.x, size.y, {
      type: options.type ?? HalfFloatType,
      depthTexture: new DepthTexture(size.x, size.y, FloatType),
      depthBuffer: true,
    });
    // three's output pass: tone mapping and the output colour space of the renderer.
    this.output = new ShaderMaterial({
      uniforms: { tDiffuse: { value: this.target.texture } },
      vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
      fragmentShader:
        'uniform sampler2D tDiffuse; varying vec2 vUv; void main() { gl_FragColor = texture2D(tDiffuse, vUv);\n#include <tonemapping_fragment>\n#include <colorspace_fragment>\n}',
      depthTest: false,
      depthWrite: false,
    });
    this.quad = new Mesh(new PlaneGeometry(2, 2), this.output);
    this.quad.frustumCulled = false;
  }

  /** The VptVolumes in `scene` that are visible. */
  volumesOf(scene: Object3D): VptVolume[] {
    const out: VptVolume[] = [];
    scene.traverseVisible((o) => {
      if (o instanceof VptVolume) out.push(o);
    });
    return out;
  }

  /** Make the vpt contexts of the scene's volumes (awaitable before the first frame). */
  async prepare(scene: Object3D): Promise<void> {
    const size = this.renderer.getDrawingBufferSize(new Vector2());
    await Promise.all(this.volumesOf(scene).map((v) => v.connect(this.renderer, size.x, size.y)));
  }

  /**
   * Draw `scene` as seen by `camera` into `output` (default: the canvas), after drawing it
   * into `target` (the linear scene image, kept for reading).
   */
  render(scene: Scene, camera: Camera, output: WebGLRenderTarget | null = null): void {
    const r = this.renderer;
    const size = r.getDrawingBufferSize(new Vector2());
    if (this.target.width !== size.x || this.target.height !== size.y) this.target.setSize(size.x, size.y);
    scene.updateMatrixWorld();
    if (camera.parent === null) camera.updateMatrixWorld();
    const volumes = this.volumesOf(scene);
    const { opaque, transparent } = splitMaterials(scene);
    const autoClear = r.autoClear;
    const background = scene.background;
    // 1. The opaque pass, with three's background and clear.
    setVisible(transparent, false);
    r.setRenderTarget(this.target);
    r.render(scene, camera);
    setVisible(transparent, true);
    // 2. The volumes.
    const props = (r as unknown as { properties: Internals }).properties;
    const depth = props.get(this.target.depthTexture!).__webglTexture ?? null;
    for (const v of volumes) {
      const hdr = v.refine(r, camera, size.x, size.y, depth);
      if (hdr && v.lastView) this.composite(hdr, camera, v, size.x, size.y);
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
    r.render(this.quad, this.quadCamera);
  }

  private composite(hdr: WebGLTexture, camera: Camera, v: VptVolume, width: number, height: number): void {
    const r = this.renderer;
    const gl = r.getContext() as WebGL2RenderingContext;
    const props = (r as unknown as { properties: Internals }).properties;
    const fb = props.get(this.target).__webglFramebuffer ?? null;
    this.programs ??= {
      colour: program(gl, COLOUR),
      depth: program(gl, DEPTH),
      vao: gl.createVertexArray()!,
    };
    const { colour, depth, vao } = this.programs;
    const view = v.lastView!;
    const localToClip = new Matrix4()
      .multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse)
      .multiply(view.toWorld);
    const clipToLocal = localToClip.clone().invert();
    const box = volumeBox(view.scene.volume);
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.viewport(0, 0, width, height);
    gl.disable(gl.SCISSOR_TEST);
    gl.disable(gl.CULL_FACE);
    gl.disable(gl.STENCIL_TEST);
    gl.bindVertexArray(vao);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, hdr);
    // Colour: rgb + (1 − a) · what is there (vpt's rgb is not multiplied by a: it is radiance).
    gl.useProgram(colour);
    gl.uniform1i(gl.getUniformLocation(colour, 'hdr'), 0);
    gl.enable(gl.BLEND);
    gl.blendEquation(gl.FUNC_ADD);
    gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
    gl.disable(gl.DEPTH_TEST);
    gl.depthMask(false);
    gl.colorMask(true, true, true, true);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    // Depth where the volume is at least half opaque, nearer than what is there.
    gl.useProgram(depth);
    gl.uniform1i(gl.getUniformLocation(depth, 'hdr'), 0);
    const guide = v.context?.depthGuideGlTextures() ?? null;
    gl.uniform1i(gl.getUniformLocation(depth, 'useGuide'), guide ? 1 : 0);
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, guide ? guide.normalDepth : hdr);
    gl.activeTexture(gl.TEXTURE2);
    gl.bindTexture(gl.TEXTURE_2D, guide ? guide.albedoHit : hdr);
    gl.uniform1i(gl.getUniformLocation(depth, 'guideDepth'), 1);
    gl.uniform1i(gl.getUniformLocation(depth, 'guideHit'), 2);
    gl.uniform3fv(gl.getUniformLocation(depth, 'eye'), view.scene.camera.position);
    gl.uniformMatrix4fv(gl.getUniformLocation(depth, 'clipToLocal'), false, clipToLocal.elements);
    gl.uniformMatrix4fv(gl.getUniformLocation(depth, 'localToClip'), false, localToClip.elements);
    gl.uniform3fv(gl.getUniformLocation(depth, 'boxMin'), box.min);
    gl.uniform3fv(gl.getUniformLocation(depth, 'boxMax'), box.max);
    gl.disable(gl.BLEND);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    gl.depthMask(true);
    gl.colorMask(false, false, false, false);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.colorMask(true, true, true, true);
    gl.bindVertexArray(null);
    r.resetState();
  }

  dispose(): void {
    this.target.dispose();
    this.quad.geometry.dispose();
    this.output.dispose();
    if (this.programs) {
      const gl = this.renderer.getContext() as WebGL2RenderingContext;
      gl.deleteProgram(this.programs.colour);
      gl.deleteProgram(this.programs.depth);
      gl.deleteVertexArray(this.programs.vao);
      this.programs = null;
    }
  }
}
