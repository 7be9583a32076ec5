/**
 * The backend conformance suite, one for both GpuBackends, run inside the headless page with
 * `page.evaluate(backendConformance, kind)` (it uses `window.vpt.core` only; typed
 * TypeScript sent as the function's source, so it may use nothing from this module's scope).
 * It checks each backend against values computed here, exactly: 3D r32float upload and
 * integer loads, uniform packing (vec3, f32, mat4), defines (bool/int/float), MRT, the
 * vptPixel() row order, two draws in a row with different uniforms, writeTexture,
 * r32float / rgba8unorm readback, canvas presentation (row 0 at the top on both), the
 * shared validation (feedback loops, the canvas-draw rule), limit and shader errors, loss and
 * restore, OffscreenCanvas, dispose. The kernels are the only per-language part.
 */
import type { GpuBackend, PassDescriptor, UniformValues } from '@vpt/core';

export interface ConformanceResult {
  failures: number;
  /** One line per check: `PASS name` or `FAIL name — detail`, plus info lines. */
  log: string[];
}

export async function backendConformance(kind: 'webgl2' | 'webgpu'): Promise<ConformanceResult> {
  const core = window.vpt.core;
  const { UniformLayout } = core;
  const log: string[] = [];
  let failures = 0;
  const check = (name: string, ok: boolean, detail = '') => {
    if (!ok) failures++;
    log.push(`${ok ? 'PASS' : 'FAIL'} ${name}${detail ? ` — ${detail}` : ''}`);
  };
  type Failure = { name?: string; code?: string; message?: string } | undefined;
  /** Run fn, expect a VptError with `code`. */
  const expectCode = async (name: string, code: string, fn: () => unknown): Promise<Failure> => {
    try {
      await fn();
      check(name, false, 'no error thrown');
      return undefined;
    } catch (err) {
      const e = err as Failure;
      check(
        name,
        e?.name === 'VptError' && e.code === code,
        `${e?.name} ${e?.code}: ${String(e?.message).split('\n')[0]}`,
      );
      return e;
    }
  };
  /** First mismatch between two arrays, or '' when they are equal element by element. */
  const firstMismatch = (got: ArrayLike<number>, want: ArrayLike<number>) => {
    if (got.length !== want.length) return `length ${got.length} != ${want.length}`;
    for (let i = 0; i < want.length; i++)
      if (!Object.is(got[i], want[i])) return `[${i}] got ${got[i]}, want ${want[i]}`;
    return '';
  };
  const gl = kind === 'webgl2';
  /** A full-screen kernel body in this backend's language: GLSL `void main()` or the WGSL fs_main returning VptOut. */
  const kernel = (glsl: string, wgsl: string) => (gl ? { glsl, wgsl: '' } : { glsl: '', wgsl });
  const wgslMain = (body: string) =>
    `@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {\n  var o: VptOut;\n${body}\n  return o;\n}`;

  const W = 8,
    H = 4,
    NZ = 3;
  const volumeValue = (x: number, y: number, z: number) => x + 10 * y + 100 * z + 0.25;
  const volumeData = (bias = 0) => {
    const d = new Float32Array(W * H * NZ);
    for (let z = 0; z < NZ; z++)
      for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) d[x + W * (y + H * z)] = volumeValue(x, y, z) + bias;
    return d;
  };

  const layout = new UniformLayout('TestParams', [
    { name: 'offset', type: 'vec3' },
    { name: 'scale', type: 'f32' },
    { name: 'm', type: 'mat4' },
  ]);
  const matrix = Array.from({ length: 16 }, (_, i) => 1.5 * i); // column-major: m[1][2] = element 6 = 9
  const uniformValues = { offset: [0.5, 3, -7], scale: 2, m: matrix };
  const uniformValuesB = { offset: [-1.5, 40, 2], scale: -3, m: matrix.map((v) => v + 1) }; // m[1][2] = 10

  const MAIN_PASS: PassDescriptor = {
    label: 'mrt test',
    uniforms: layout,
    textures: [{ name: 'vol', dimension: '3d' }],
    outputs: ['rgba32float', 'rgba32float'],
    defines: { HALF: 0.5, FLAG: true, OFF: false, SEVEN: 7 },
    ...kernel(
      `
void main() {
  ivec2 p = vptPixel();
  ivec2 size = vptTargetSize();
  float v = texelFetch(vol, ivec3(p, 1), 0).r;
  vpt_out0 = vec4(v * u.scale + u.offset.x,
                  u.offset.y + float(size.x * 10 + size.y),
                  u.offset.z + float(OFF) + float(SEVEN),
                  u.m[1][2] + HALF + float(FLAG));
  vpt_out1 = vec4(vptPixel(), 0, 1);
}
`,
      `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let size = vptTargetSize();
  let v = textureLoad(vol, vec3i(p, 1), 0).r;
  var o: VptOut;
  o.out0 = vec4f(v * u.scale + u.offset.x,
                 u.offset.y + f32(size.x * 10 + size.y),
                 u.offset.z + select(0.0, 1.0, OFF) + f32(SEVEN),
                 u.m[1][2] + HALF + select(0.0, 1.0, FLAG));
  o.out1 = vec4f(vec2f(p), 0.0, 1.0);
  return o;
}
`,
    ),
  };
  const expectedMain = (bias = 0, values: typeof uniformValues = uniformValues) => {
    const a = new Float32Array(W * H * 4),
      b = new Float32Array(W * H * 4);
    const f = Math.fround;
    for (let y = 0; y < H; y++)
      for (let x = 0; x < W; x++) {
        const i = 4 * (x + W * y);
        const v = f(volumeValue(x, y, 1) + bias);
        a.set(
          [
            f(f(v * values.scale) + values.offset[0]),
            values.offset[1] + (W * 10 + H),
            values.offset[2] + 0 + 7,
            values.m[6] + 0.5 + 1,
          ],
          i,
        );
        b.set([x, y, 0, 1], i);
      }
    return [a, b];
  };

  const R32_PASS: PassDescriptor = {
    label: 'r32 test',
    uniforms: new UniformLayout('NoParams', []),
    textures: [],
    outputs: ['r32float'],
    ...kernel(
      'void main() { ivec2 p = vptPixel(); vpt_out0 = vec4(float(p.x + p.y * vptTargetSize().x) + 0.5, 9.0, 9.0, 9.0); }',
      wgslMain(
        '  let p = vptPixel(fragCoord);\n  o.out0 = vec4f(f32(p.x + p.y * vptTargetSize().x) + 0.5, 9.0, 9.0, 9.0);',
      ),
    ),
  };
  const RGBA8_PASS: PassDescriptor = {
    label: 'rgba8 test',
    uniforms: new UniformLayout('Rgba8Params', [{ name: 'pad', type: 'f32' }]),
    textures: [],
    outputs: ['rgba8unorm'],
    ...kernel(
      'void main() { ivec2 p = vptPixel(); vpt_out0 = vec4(float(p.x * 10) / 255.0, float(p.y * 20) / 255.0, 1.0, 1.0); }',
      wgslMain(
        '  let p = vptPixel(fragCoord);\n  o.out0 = vec4f(f32(p.x * 10) / 255.0, f32(p.y * 20) / 255.0, 1.0, 1.0);',
      ),
    ),
  };
  const expectedRgba8 = () => {
    const e = new Uint8Array(W * H * 4);
    for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) e.set([x * 10, y * 20, 255, 255], 4 * (x + W * y));
    return e;
  };
  const PRESENT_PASS: PassDescriptor = {
    label: 'present test',
    uniforms: new UniformLayout('PresentParams', [{ name: 'pad', type: 'f32' }]),
    textures: [{ name: 'inputImage', dimension: '2d' }],
    outputs: ['rgba8unorm'],
    ...kernel(
      'void main() { vpt_out0 = texelFetch(inputImage, vptPixel(), 0); }',
      wgslMain('  o.out0 = textureLoad(inputImage, vptPixel(fragCoord), 0);'),
    ),
  };
  const pad = (v: UniformValues = { pad: 0 }) => RGBA8_PASS.uniforms.pack(v);

  /** Create the 3D texture, MRT target and pass; draw; read both outputs back and compare. */
  const runMain = async (backend: GpuBackend, tag: string, bias = 0) => {
    const vol = backend.createTexture({
      dimension: '3d',
      width: W,
      height: H,
      depth: NZ,
      format: 'r32float',
      data: volumeData(bias),
      label: 'vol',
    });
    const target = backend.createRenderTarget(W, H, ['rgba32float', 'rgba32float'], 'mrt');
    const pass = backend.createPass(MAIN_PASS);
    backend.draw(pass, { uniforms: layout.pack(uniformValues), textures: { vol }, target });
    const [a, b] = await Promise.all(target.textures.map((t) => backend.readTexture(t)));
    const [ea, eb] = expectedMain(bias);
    check(
      `${tag}: output 0 (3D integer load + uniforms + defines + target size) exact`,
      a instanceof Float32Array && !firstMismatch(a, ea),
      firstMismatch(a, ea),
    );
    check(
      `${tag}: output 1 (vptPixel) exact`,
      b instanceof Float32Array && !firstMismatch(b, eb),
      firstMismatch(b, eb),
    );
    check(
      `${tag}: readback row 0 is pixel row 0 from the top`,
      b[1] === 0 && b[4 * W * (H - 1) + 1] === H - 1,
      `row0.y=${b[1]} lastRow.y=${b[4 * W * (H - 1) + 1]}`,
    );
    return { vol, target, pass };
  };
  const create = async (canvas: HTMLCanvasElement | OffscreenCanvas): Promise<GpuBackend> =>
    gl ? core.createWebGL2Backend(canvas) : core.createWebGPUBackend(canvas);
  /** What the canvas shows, read through a 2D canvas. */
  const shownOn = (canvas: HTMLCanvasElement) => {
    const c2 = document.createElement('canvas');
    c2.width = W;
    c2.height = H;
    const ctx = c2.getContext('2d')!;
    ctx.drawImage(canvas, 0, 0);
    return new Uint8Array(ctx.getImageData(0, 0, W, H).data.buffer);
  };
  const program = (p: unknown) => (p as { program: unknown }).program;

  try {
    if (!gl) check('isWebGPUAvailable()', (await core.isWebGPUAvailable()) === true);
    const canvas = document.createElement('canvas');
    const backend = await create(canvas);
    log.push(`info: ${JSON.stringify(backend.info)} limits: ${JSON.stringify(backend.limits)}`);
    check(`kind is ${kind}`, backend.kind === kind && backend.info.kind === kind);
    check('limits are positive', backend.limits.maxTextureDimension2D > 0 && backend.limits.maxTextureDimension3D > 0);
    backend.resizeCanvas(W, H);
    check('resizeCanvas', canvas.width === W && canvas.height === H);

    const lostCalls: number[] = [],
      restoredCalls: number[] = [];
    backend.onLost(() => lostCalls.push(performance.now()));
    backend.onRestored(() => restoredCalls.push(performance.now()));

    const first = await runMain(backend, 'initial');

    // Program / pipeline cache: an equal descriptor reuses the compiled program.
    const again = backend.createPass({ ...MAIN_PASS });
    check('cache hit for an equal descriptor', program(again) === program(first.pass));
    const other = backend.createPass({ ...MAIN_PASS, defines: { ...MAIN_PASS.defines, SEVEN: 8 } });
    check('different defines compile a different program', program(other) !== program(first.pass));

    // Two draws in a row with different uniforms, each into its own target, read afterwards.
    {
      const t2 = backend.createRenderTarget(W, H, ['rgba32float', 'rgba32float'], 'mrt B');
      backend.draw(first.pass, {
        uniforms: layout.pack(uniformValues),
        textures: { vol: first.vol },
        target: first.target,
      });
      backend.draw(first.pass, { uniforms: layout.pack(uniformValuesB), textures: { vol: first.vol }, target: t2 });
      const [a1, a2] = await Promise.all([
        backend.readTexture(first.target.textures[0]),
        backend.readTexture(t2.textures[0]),
      ]);
      const [e1] = expectedMain(0, uniformValues),
        [e2] = expectedMain(0, uniformValuesB);
      check('two draws in a row: first sees its own uniforms', !firstMismatch(a1, e1), firstMismatch(a1, e1));
      check('two draws in a row: second sees its own uniforms', !firstMismatch(a2, e2), firstMismatch(a2, e2));
      backend.destroyRenderTarget(t2);
    }

    // writeTexture replaces the volume; the same pass sees the new values.
    backend.writeTexture(first.vol, volumeData(1000));
    backend.draw(first.pass, {
      uniforms: layout.pack(uniformValues),
      textures: { vol: first.vol },
      target: first.target,
    });
    {
      const a = await backend.readTexture(first.target.textures[0]);
      const [ea] = expectedMain(1000);
      check('writeTexture: new data is read by the kernel', !firstMismatch(a, ea), firstMismatch(a, ea));
    }

    // r32float: readback is tightly packed, one float per texel (and a layout without fields works).
    {
      const t = backend.createRenderTarget(W, H, ['r32float'], 'r32');
      backend.draw(backend.createPass(R32_PASS), { uniforms: new ArrayBuffer(16), textures: {}, target: t });
      const r = await backend.readTexture(t.textures[0]);
      const e = Float32Array.from({ length: W * H }, (_, i) => i + 0.5);
      check('r32float readback (W*H floats)', r instanceof Float32Array && !firstMismatch(r, e), firstMismatch(r, e));
      backend.destroyRenderTarget(t);
    }

    // rgba8unorm target, then present it to the canvas: row 0 at the top on both backends
    // (WebGL 2 flips rows for GL's bottom-up canvas; WebGPU needs no flip).
    {
      const t = backend.createRenderTarget(W, H, ['rgba8unorm'], 'ldr');
      backend.draw(backend.createPass(RGBA8_PASS), { uniforms: pad(), textures: {}, target: t });
      const r = await backend.readTexture(t.textures[0]);
      const e = expectedRgba8();
      check('rgba8unorm readback exact', r instanceof Uint8Array && !firstMismatch(r, e), firstMismatch(r, e));

      const present = backend.createPass(PRESENT_PASS);
      backend.draw(present, { uniforms: pad(), textures: { inputImage: t.textures[0] }, target: 'canvas' });
      await backend.finish();
      const shown = shownOn(canvas);
      check('canvas shows row 0 at the top', !firstMismatch(shown, e), firstMismatch(shown, e));

      let feedback = '';
      try {
        backend.draw(present, { uniforms: new ArrayBuffer(16), textures: { inputImage: t.textures[0] }, target: t });
      } catch (err) {
        feedback = (err as Error).message;
      }
      check('reading the texture being written is refused', /feedback/.test(feedback), feedback);

      // The shared canvas-draw rule: one rgba8unorm output, on both backends.
      const hdrToCanvas = backend.createPass({
        ...PRESENT_PASS,
        label: 'hdr to canvas',
        outputs: ['rgba32float'],
        ...kernel(
          'void main() { vpt_out0 = texelFetch(inputImage, vptPixel(), 0); }',
          wgslMain('  o.out0 = textureLoad(inputImage, vptPixel(fragCoord), 0);'),
        ),
      });
      let canvasRule = '';
      try {
        backend.draw(hdrToCanvas, { uniforms: pad(), textures: { inputImage: t.textures[0] }, target: 'canvas' });
      } catch (err) {
        canvasRule = (err as Error).message;
      }
      check(
        'a canvas draw with an rgba32float output is refused',
        /one rgba8unorm output/.test(canvasRule),
        canvasRule,
      );
      backend.destroyRenderTarget(t);
    }

    // Limits: checked before the API would fail.
    const max3 = backend.limits.maxTextureDimension3D,
      max2 = backend.limits.maxTextureDimension2D;
    const name3 = gl ? 'MAX_3D_TEXTURE_SIZE' : 'maxTextureDimension3D',
      name2 = gl ? 'MAX_TEXTURE_SIZE' : 'maxTextureDimension2D';
    const e3 = await expectCode(`3D texture of ${name3}+1 (${max3 + 1}) → limit-exceeded`, 'limit-exceeded', () =>
      backend.createTexture({ dimension: '3d', width: 1, height: 1, depth: max3 + 1, format: 'r32float' }),
    );
    check(
      'limit message names the limit and the size',
      new RegExp(name3).test(String(e3?.message)) && String(e3?.message).includes(String(max3 + 1)),
      e3?.message,
    );
    await expectCode(`2D texture of ${name2}+1 (${max2 + 1}) → limit-exceeded`, 'limit-exceeded', () =>
      backend.createRenderTarget(max2 + 1, 1, ['rgba32float']),
    );

    // Shader errors: WebGL 2 compiles at createPass; WebGPU finds them asynchronously (the
    // next finish() rejects, then createPass throws at once).
    const BROKEN: PassDescriptor = {
      ...R32_PASS,
      label: 'broken kernel',
      ...kernel('void main() {\n  vpt_out0 = vec4(notDeclared);\n}\n', wgslMain('  o.out0 = vec4f(notDeclared);')),
    };
    const brokenLine = gl ? /\d+\|\s+vpt_out0 = vec4\(notDeclared\);/ : /\d+\|\s+o\.out0 = vec4f\(notDeclared\);/;
    const es = await expectCode('broken shader → shader-compile', 'shader-compile', async () => {
      const t = backend.createRenderTarget(W, H, ['r32float'], 'r32 broken');
      const p = backend.createPass(BROKEN);
      backend.draw(p, { uniforms: new ArrayBuffer(16), textures: {}, target: t });
      await backend.finish();
    });
    check(
      'compile error names the label, has the log and numbered source lines',
      /broken kernel/.test(String(es?.message)) &&
        /notDeclared/.test(String(es?.message)) &&
        brokenLine.test(String(es?.message)),
      '',
    );
    log.push(`(shader error message)\n${es?.message}`);
    await expectCode('broken shader, second createPass → shader-compile at once', 'shader-compile', () =>
      backend.createPass(BROKEN),
    );
    await backend.finish();
    check('the error is reported once: a later finish() resolves', true);
    if (!gl) {
      await expectCode('broken shader → readTexture rejects with shader-compile', 'shader-compile', async () => {
        const t = backend.createRenderTarget(W, H, ['r32float'], 'r32 broken 2');
        backend.draw(
          backend.createPass({
            ...BROKEN,
            label: 'broken kernel 2',
            wgsl: BROKEN.wgsl.replace('notDeclared', 'alsoMissing'),
          }),
          { uniforms: new ArrayBuffer(16), textures: {}, target: t },
        );
        await backend.readTexture(t.textures[0]);
      });
      // A kernel whose outputs do not match VptOut fails at pipeline creation, not in the compiler.
      const em = await expectCode('kernel/pipeline mismatch → shader-compile', 'shader-compile', async () => {
        const t = backend.createRenderTarget(W, H, ['r32float'], 'r32 mismatch');
        // Writes location 1 only, while the target (and pipeline) has a colour target at location 0.
        const wgsl =
          '@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> @location(1) vec4f { return vec4f(1.0); }';
        backend.draw(backend.createPass({ ...R32_PASS, label: 'no VptOut', wgsl }), {
          uniforms: new ArrayBuffer(16),
          textures: {},
          target: t,
        });
        await backend.finish();
      });
      log.push(`(pipeline error message)\n${em?.message}`);
    }

    // Loss: while lost, draw is a no-op and readTexture rejects with context-lost.
    const duringLoss: {
      value: { drawThrew: unknown; isLost: boolean; read: Promise<Failure | null>; created: boolean } | null;
    } = { value: null };
    backend.onLost(() => {
      let drawThrew: unknown = null;
      try {
        backend.draw(first.pass, {
          uniforms: layout.pack(uniformValues),
          textures: { vol: first.vol },
          target: first.target,
        });
      } catch (e) {
        drawThrew = e;
      }
      const t = backend.createTexture({ dimension: '2d', width: 2, height: 2, format: 'rgba32float' });
      duringLoss.value = {
        drawThrew,
        isLost: backend.isLost,
        read: backend.readTexture(first.target.textures[0]).then(
          () => null,
          (e) => e as Failure,
        ),
        created: !!t,
      };
    });
    await backend.simulateLoss(50);
    check(
      'onLost and onRestored each fired once',
      lostCalls.length === 1 && restoredCalls.length === 1 && restoredCalls[0] >= lostCalls[0],
      `${lostCalls.length}/${restoredCalls.length}`,
    );
    check('isLost is false after restore', backend.isLost === false);
    const during = duringLoss.value;
    check(
      'during loss: isLost, draw is a no-op, createTexture works',
      !!during && during.isLost && during.drawThrew === null && during.created,
      String(during?.drawThrew),
    );
    const readErr = during && (await during.read);
    check('during loss: readTexture rejects with context-lost', readErr?.code === 'context-lost', `${readErr?.code}`);
    await expectCode('after restore, an old pass is refused clearly', 'context-lost', () =>
      backend.draw(first.pass, {
        uniforms: layout.pack(uniformValues),
        textures: { vol: first.vol },
        target: first.target,
      }),
    );
    backend.destroyTexture(first.vol); // stale objects can still be destroyed without errors
    backend.destroyRenderTarget(first.target);
    check('destroying stale objects is silent', true);
    await runMain(backend, 'after restore');
    // The canvas presents again after the restore.
    {
      const t = backend.createRenderTarget(W, H, ['rgba8unorm'], 'ldr 2');
      backend.draw(backend.createPass(RGBA8_PASS), { uniforms: pad(), textures: {}, target: t });
      backend.draw(backend.createPass(PRESENT_PASS), {
        uniforms: pad(),
        textures: { inputImage: t.textures[0] },
        target: 'canvas',
      });
      await backend.finish();
      const shown = shownOn(canvas);
      check(
        'after restore: canvas presentation works',
        !firstMismatch(shown, expectedRgba8()),
        firstMismatch(shown, expectedRgba8()),
      );
    }
    await backend.finish();

    // An OffscreenCanvas works too (workers use one).
    if (typeof OffscreenCanvas !== 'undefined') {
      const off = await create(new OffscreenCanvas(1, 1));
      await runMain(off, 'OffscreenCanvas');
      off.dispose();
    }

    // Dispose.
    let lostAfterDispose = 0;
    if (!gl) backend.onLost(() => lostAfterDispose++);
    backend.dispose();
    await expectCode('use after dispose → disposed', 'disposed', () =>
      backend.createTexture({ dimension: '2d', width: 1, height: 1, format: 'rgba8unorm' }),
    );
    if (gl) {
      check('dispose loses the context', canvas.getContext('webgl2')?.isContextLost() === true);
    } else {
      await new Promise((r) => setTimeout(r, 200));
      check(
        'dispose does not fire onLost or restore',
        lostAfterDispose === 0 && restoredCalls.length === 1,
        `${lostAfterDispose}/${restoredCalls.length}`,
      );
    }
  } catch (err) {
    const e = err as { name?: string; code?: string; message?: string; stack?: string };
    check('unexpected error', false, `${e?.name} ${e?.code ?? ''}: ${e?.message}\n${e?.stack}`);
  }
  log.push(failures === 0 ? 'ALL PASS' : `${failures} FAILED`);
  return { failures, log };
}
