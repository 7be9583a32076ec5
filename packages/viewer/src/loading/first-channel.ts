/** The element's view of a multichannel load until it has a Channels panel (a lazy chunk of volume-source.ts). */
import { channelVolume } from '@vpt/core';
import type { LoadedVolumeLike } from './types.js';

/** Channel 0 of a multichannel load as a scalar volume, keeping its placement and meta. */
export function firstChannel(volume: LoadedVolumeLike): LoadedVolumeLike {
  const one = channelVolume(volume, 0);
  // Every field but the data range (a getter over all channels' voxels): channel 0's own.
  const meta: Record<string, unknown> = {};
  for (const k of Object.keys(volume.meta ?? {})) if (k !== 'dataRange') meta[k] = volume.meta![k];
  let min = Infinity,
    max = -Infinity;
  for (let i = 0; i < one.data.length; i++) {
    const x = one.data[i];
    if (x < min) min = x;
    if (x > max) max = x;
  }
  if (min <= max) meta.dataRange = [min, max];
  const warnings = Array.isArray(meta.warnings) ? [...(meta.warnings as string[])] : [];
  warnings.push(`the file holds ${volume.channels} channels; the viewer shows channel 0`);
  const { channels: _all, data: _data, ...rest } = volume;
  void _all;
  void _data;
  return { ...rest, data: one.data, meta: { ...meta, warnings, channelCount: volume.channels } };
}
