#!/usr/bin/env node
/**
 * Memory per channel with bricking (issue 24 item 1, core/src/bricking with BrickChannels): a
 * uint8 volume of 1–4 drawn channels (a Gaussian ball shifted per channel, 0 far from it),
 *  - bricked with room for everything ('force'): atlas slots, bytes per slot, atlas + tables
 *    bytes, and those bytes per drawn channel, against the unbricked channel texture's bytes;
 *  - bricked under one fixed budget ('auto', half the 4-channel texture): slots and level-0
 *    bricks served by their own data, per channel count (the budget counts every drawn channel);
 *  - EAM ms per iteration bricked against unbricked per channel count, interleaved
 *    (U B B U … per round), as a median ratio.
 *
 *   pnpm run build && node benchmarks/bricking-channels.mjs [--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu] [--brick N]
 *
 * Prints one line per channel count and one JSON line, with the load average.
 */
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const {
  size,
  volume,
  rounds,
  batch,
  backend,
  brick: brickSize,
} = parseCliOrExit({
  name: 'node benchmarks/bricking-channels.mjs',
  synopsis: '[--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu] [--brick N]',
  summary:
    'Bytes of the brick atlas per drawn channel (1–4) and bricked / unbricked EAM ms per iteration (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 64, description: 'image side in pixels' },
    volume: { type: 'integer', min: 8, default: 96, description: 'volume side in voxels' },
    rounds: { type: 'integer', min: 1, default: 3, description: 'U B B U rounds' },
    batch: { type: 'integer', min: 1, default: 4, description: 'iterations per timed batch' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
    brick: { type: 'integer', min: 4, default: 16, description: 'brick side in voxels' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');
const loadBefore = load();

const session = await openVptPage();
try {
  const rows = await session.page.evaluate(
    async (o) => {
      const { core } = window.vpt;
      const n = o.volume;
      // Channel k: a Gaussian ball (radius 0.2 of the box) centred 0.05k off the middle along x,
      // as uint8: 0 far from it (empty space, so bricks away from it are constant in every channel).
      const field = (k) => {
        const d = new Uint8Array(n * n * n);
        let i = 0;
        for (let z = 0; z < n; z++)
          for (let y = 0; y < n; y++)
            for (let x = 0; x < n; x++, i++) {
              const q =
                ((x + 0.5) / n - 0.45 - 0.05 * k) ** 2 + ((y + 0.5) / n - 0.5) ** 2 + ((z + 0.5) / n - 0.5) ** 2;
              d[i] = Math.round(255 * Math.exp(-q / 0.04));
            }
        return d;
      };
      const parts = [0, 1, 2, 3].map((k) => core.createVolume([n, n, n], 'uint8', field(k)));
      const all = core.interleaveChannels(parts);
      const tf = (c) => ({
        dimensions: '1d',
        points: [
          { value: 0, color: c, opacity: 0 },
          { value: 0.2, color: c, opacity: 0 },
          { value: 1, color: c, opacity: 1 },
        ],
      });
      const colours = [
        [0.9, 0.3, 0.2],
        [0.2, 0.9, 0.3],
        [0.3, 0.4, 0.95],
        [0.9, 0.9, 0.2],
      ];
      const sceneOf = (count) => ({
        volume: all,
        transferFunction: tf(colours[0]),
        channels: colours.map((c, k) => ({ transferFunction: tf(c), enabled: k < count })),
        camera: { position: [0.9, 0.6, 1.3], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
        lights: [],
        environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
        densityScale: 30,
        seed: 1,
      });
      const renderer = () => window.vpt.createRenderer('eam', {});
      const make = async (count, bricking, maxGpuBytes) => {
        const ctx = await core.RenderContext.create({
          backend: o.backend,
          width: o.size,
          height: o.size,
          renderer: renderer(),
          bricking,
          brickSize: o.brick,
          ...(maxGpuBytes ? { maxGpuBytes } : {}),
        });
        ctx.onWarning(() => {});
        ctx.setScene(sceneOf(count));
        await ctx.whenBricksSettled();
        await ctx.renderIterations(1); // compile, untimed
        return ctx;
      };
      // One fixed budget for every channel count: the targets and TF allowance plus half the 4-channel texture.
      const probe = await make(1, 'off');
      const targets = probe.maxGpuBytes - probe.volumeBudgetBytes;
      probe.dispose();
      const fixed = targets + (4 * n * n * n) / 2;
      const out = [];
      for (const count of [1, 2, 3, 4]) {
        const plain = await make(count, 'off');
        const full = await make(count, 'force');
        const capped = await make(count, 'auto', fixed);
        const ms = { plain: [], bricked: [] };
        for (let r = 0; r < o.rounds; r++)
          for (const [k, ctx] of r % 2
            ? [
                ['bricked', full],
                ['plain', plain],
              ]
            : [
                ['plain', plain],
                ['bricked', full],
              ]) {
            const t0 = performance.now();
            await ctx.renderIterations(o.batch);
            ms[k].push((performance.now() - t0) / o.batch);
          }
        const b = full.stats.bricking;
        const c = capped.stats.bricking;
        const S = o.brick + 2;
        out.push({
          channels: count,
          texture: plain.stats.gpuBytes.volume,
          atlasBytes: b.gpuBytes,
          slots: b.slots,
          constant: b.constant,
          bytesPerSlotTexel: plain.stats.gpuBytes.volume / (n * n * n),
          slotSide: S,
          fixedBudget: fixed - targets,
          fixedSlots: c ? c.slots : 0,
          fixedFinest: c ? c.finest : null,
          level0Bricks: Math.ceil(n / o.brick) ** 3,
          ms,
        });
        [plain, full, capped].forEach((x) => x.dispose());
      }
      return out;
    },
    { backend, size, volume, rounds, batch, brick: brickSize },
  );
  const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
  console.log(
    `bricking-channels: ${backend}, ${size}² px, ${volume}³ uint8, brick ${brickSize}, ${rounds} rounds of ${batch}; load before ${loadBefore}`,
  );
  const json = [];
  for (const r of rows) {
    const slotBytes = r.bytesPerSlotTexel * r.slotSide ** 3;
    const ratio = median(r.ms.bricked.map((m, i) => m / r.ms.plain[i]));
    const line = {
      channels: r.channels,
      textureBytes: r.texture,
      atlasBytes: r.atlasBytes,
      atlasBytesPerChannel: Math.round(r.atlasBytes / r.channels),
      slots: r.slots,
      constantBricks: r.constant,
      slotBytes,
      fixedBudgetBytes: r.fixedBudget,
      fixedBudget:
        r.fixedFinest === null
          ? 'fits unbricked'
          : `bricked, ${r.fixedSlots} slots, level 0 serves ${r.fixedFinest}/${r.level0Bricks}`,
      eamMsPlain: +median(r.ms.plain).toFixed(2),
      eamMsBricked: +median(r.ms.bricked).toFixed(2),
      bricked_over_plain: +ratio.toFixed(3),
    };
    json.push(line);
    console.log(
      `${r.channels} ch: texture ${(r.texture / 2 ** 20).toFixed(2)} MiB; atlas+tables ${(r.atlasBytes / 2 ** 20).toFixed(2)} MiB ` +
        `(${r.slots} slots of ${slotBytes} B, ${r.constant} constant bricks; ${(r.atlasBytes / r.channels / 2 ** 20).toFixed(2)} MiB per channel); ` +
        `under ${(r.fixedBudget / 2 ** 20).toFixed(2)} MiB: ${line.fixedBudget}; ` +
        `EAM ${line.eamMsBricked} / ${line.eamMsPlain} ms/it bricked/plain ×${line.bricked_over_plain}`,
    );
  }
  console.log(JSON.stringify({ backend, size, volume, brick: brickSize, rows: json, loadBefore, loadAfter: load() }));
} finally {
  await session.close();
}
