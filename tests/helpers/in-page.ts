/**
 * Code that runs inside the page (page.evaluate). Kept as one function source that
 * tests install once, so each test's evaluate body stays short.
 */
export const IN_PAGE_HELPERS = `
window.t = {
  async context(opts) {
    const { core, mip, eam, mcrt, iso, post } = window.vpt;
    const renderer = opts.renderer === 'mip' ? new mip.MipRenderer(opts.params || {})
      : opts.renderer === 'mcrt' ? new mcrt.McrtRenderer(opts.params || {})
      : opts.renderer === 'iso' ? new iso.IsoRenderer(opts.params || {})
      : new eam.EamRenderer(opts.params || {});
    const steps = opts.post ? post.postChainFromJSON(opts.post) : [];
    // sampling: 'exact' for tests that compare with CPU twins or across backends bit for bit.
    return core.RenderContext.create({ backend: opts.backend, width: opts.width, height: opts.height, renderer, post: steps, sampling: opts.sampling, maxGpuBytes: opts.maxGpuBytes });
  },
  scene(spec) {
    const { core } = window.vpt;
    return {
      volume: spec.volume,
      transferFunction: spec.transferFunction || core.rampTransferFunction(),
      camera: spec.camera || core.defaultCamera(),
      lights: [],
      environment: spec.environment || { type: 'constant', radiance: [0, 0, 0] },
      densityScale: spec.densityScale ?? 1,
      seed: spec.seed ?? 1,
      ...(spec.sampling ? { sampling: spec.sampling } : {}),
    };
  },
  async loadRaw(url, dims, type) {
    const { core } = window.vpt;
    const buf = await (await fetch(url)).arrayBuffer();
    const C = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array }[type];
    return core.createVolume(dims, type, new C(buf));
  },
  sameBits(a, b) {
    const x = new Uint32Array(a.buffer, a.byteOffset, a.byteLength / 4), y = new Uint32Array(b.buffer, b.byteOffset, b.byteLength / 4);
    if (x.length !== y.length) return -1;
    let diff = 0;
    for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) diff++;
    return diff;
  },
  hasNonFinite(a) { for (let i = 0; i < a.length; i++) if (!Number.isFinite(a[i])) return true; return false; },
};
`;
