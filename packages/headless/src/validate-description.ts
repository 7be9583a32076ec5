/**
 * The full check of a scene description, before any file is read or a browser started:
 * every field through core's shared validators (float32 range, limits, required fields,
 * unknown keys at every level, renderer parameters against the renderer's declared ranges),
 * so a bad scene file fails at once with a VptError naming the field and the limit.
 * Loaded by the CLI in Node and by the headless page (after its packages loaded).
 */
import { BACKEND_NAMES, VOLUME_FILE_FORMATS, type RendererName, type SceneDescription } from './scene-description.js';
import {
  checkKnownKeys,
  checkNumber,
  countUpTo,
  checkNumbers,
  checkObject,
  checkOneOf,
  checkString,
  defaultCamera,
  FLOAT32_MAX,
  MAX_DENSITY_SCALE,
  MAX_ITERATIONS,
  rendererNames,
  MAX_PROCEDURAL_SIZE,
  MAX_RENDER_SIDE,
  LATLONG_SIDE_RULE,
  transferFunctionFromJSON,
  validateCamera,
  validateClip,
  resolveSlicePlane,
  validateEnvironment,
  validateLights,
  DEFAULT_RENDERER_NAME,
  MAX_VOLUME_CHANNELS,
  MAX_OPACITY,
  RENDERER_CATALOG,
  validateRendererParams,
  VptError,
  type Camera,
  type Environment,
  type Light,
} from '@vpt/core';
import { postChainFromJSON } from '@vpt/post';
import { checkJsonShape } from './json-shape.js';
import { RENDERER_DESCRIPTORS } from './renderers.generated.js';

const TOP_KEYS = [
  'width',
  'height',
  'renderer',
  'rendererParams',
  'volume',
  'transferFunction',
  'camera',
  'lights',
  'environment',
  'densityScale',
  'seed',
  'sampling',
  'clip',
  'slicePlane',
  'maxGpuBytes',
  'post',
  'iterations',
  'backend',
  'time',
  'channels',
  'labels',
];
/** Volumes a description may list as channels (core's MAX_VOLUME_CHANNELS). */
const MAX_LISTED_CHANNELS = MAX_VOLUME_CHANNELS;
const VOXEL_TYPES = ['uint8', 'uint16', 'int16', 'float32'] as const;
const PROCEDURAL_KINDS = ['sphere', 'cube', 'ramp', 'blob'] as const;
/** Largest volume side a description may name; the device's maxTextureDimension3D is checked at setScene. */
export const MAX_VOLUME_SIDE = 2048;

/**
 * Renderer parameters of each renderer of core's RENDERER_CATALOG, checked by its descriptor:
 * declared ranges and unknown keys, then the descriptor's rules across them.
 */
export const RENDERER_PARAM_CHECKS: Record<RendererName, (params: unknown) => void> = Object.fromEntries(
  RENDERER_CATALOG.flatMap((e) => {
    const descriptor = RENDERER_DESCRIPTORS[e.packageName];
    return descriptor ? [[e.name, (p: unknown) => validateRendererParams(descriptor, p)]] : [];
  }),
);

function checkVolume(v: unknown, at = 'volume'): void {
  const vol = checkObject(at, v);
  if ('channels' in vol && !('zarr' in vol)) {
    // Several files of one grid, one per channel.
    checkKnownKeys(at, vol, ['channels']);
    const list = vol.channels;
    if (!Array.isArray(list) || list.length < 1 || list.length > MAX_LISTED_CHANNELS)
      throw new VptError(
        'invalid-scene',
        `${at}.channels: a list of 1 to ${MAX_LISTED_CHANNELS} volume descriptions (one per channel), got ${JSON.stringify(list)?.slice(0, 80)}`,
      );
    list.forEach((c, i) => {
      if (c && typeof c === 'object' && 'channels' in c)
        throw new VptError('invalid-scene', `${at}.channels[${i}]: a channel is one volume, not a list`);
      checkVolume(c, `${at}.channels[${i}]`);
    });
    return;
  }
  if ('raw' in vol) {
    checkKnownKeys(at, vol, ['raw', 'dims', 'type', 'spacing', 'valueRange', 'endianness']);
    checkString('volume.raw', vol.raw);
    checkNumbers('volume.dims', vol.dims, 3, countUpTo(MAX_VOLUME_SIDE, 'voxels'));
    checkOneOf('volume.type', vol.type, VOXEL_TYPES);
    if (vol.spacing !== undefined) checkNumbers('volume.spacing', vol.spacing, 3, { min: 0, exclusiveMin: true });
    if (vol.valueRange !== undefined) {
      const [lo, hi] = checkNumbers('volume.valueRange', vol.valueRange, 2);
      if (lo === hi)
        throw new VptError('invalid-scene', `volume.valueRange: min and max are equal (${lo}), an empty range`);
    }
    if (vol.endianness !== undefined) checkOneOf('volume.endianness', vol.endianness, ['little', 'big'] as const);
  } else if ('sidecar' in vol) {
    checkKnownKeys(at, vol, ['sidecar']);
    checkString('volume.sidecar', vol.sidecar);
  } else if ('zarr' in vol) {
    checkKnownKeys(at, vol, ['zarr', 'level', 'channel', 'channels', 'time', 'valueRange', 'missingChunks']);
    if (vol.channels !== undefined) {
      if (vol.channel !== undefined)
        throw new VptError('invalid-scene', `${at}: give "channel" (one) or "channels" (several), not both`);
      const list = vol.channels;
      if (!Array.isArray(list) || list.length < 1 || list.length > MAX_LISTED_CHANNELS)
        throw new VptError(
          'invalid-scene',
          `${at}.channels: a list of 1 to ${MAX_LISTED_CHANNELS} channel indices along the c axis, got ${JSON.stringify(list)?.slice(0, 80)}`,
        );
      list.forEach((c, i) => checkNumber(`${at}.channels[${i}]`, c, { min: 0, max: 1e6, integer: true }));
    }
    checkString('volume.zarr', vol.zarr);
    for (const k of ['level', 'channel', 'time'] as const)
      if (vol[k] !== undefined) checkNumber(`volume.${k}`, vol[k], { min: 0, max: 1e6, integer: true });
    if (vol.valueRange !== undefined) {
      const [lo, hi] = checkNumbers('volume.valueRange', vol.valueRange, 2);
      if (lo === hi)
        throw new VptError('invalid-scene', `volume.valueRange: min and max are equal (${lo}), an empty range`);
    }
    if (vol.missingChunks !== undefined)
      checkOneOf('volume.missingChunks', vol.missingChunks, ['error', 'fill'] as const);
  } else if ('timeSeries' in vol) {
    checkKnownKeys('volume', vol, ['timeSeries', 'format', 'valueRange']);
    if (!Array.isArray(vol.timeSeries) || vol.timeSeries.length === 0)
      throw new VptError('invalid-scene', 'volume.timeSeries: must be a non-empty list of files, one per time step');
    vol.timeSeries.forEach((f, i) => {
      if (Array.isArray(f)) f.forEach((g, j) => checkString(`volume.timeSeries[${i}][${j}]`, g));
      else checkString(`volume.timeSeries[${i}]`, f);
    });
    if (vol.format !== undefined) checkOneOf('volume.format', vol.format, VOLUME_FILE_FORMATS);
    if (vol.valueRange !== undefined) {
      const [lo, hi] = checkNumbers('volume.valueRange', vol.valueRange, 2);
      if (lo === hi)
        throw new VptError('invalid-scene', `volume.valueRange: min and max are equal (${lo}), an empty range`);
    }
  } else if ('file' in vol) {
    checkKnownKeys(at, vol, ['file', 'format', 'valueRange', 'time']);
    if (vol.time !== undefined) checkNumber('volume.time', vol.time, { min: 0, max: 1e6, integer: true });
    if (Array.isArray(vol.file)) {
      if (!vol.file.length) throw new VptError('invalid-scene', 'volume.file: an empty list names no file');
      vol.file.forEach((f, i) => checkString(`volume.file[${i}]`, f));
    } else checkString('volume.file', vol.file);
    if (vol.format !== undefined) checkOneOf('volume.format', vol.format, VOLUME_FILE_FORMATS);
    if (vol.valueRange !== undefined) {
      const [lo, hi] = checkNumbers('volume.valueRange', vol.valueRange, 2);
      if (lo === hi)
        throw new VptError('invalid-scene', `volume.valueRange: min and max are equal (${lo}), an empty range`);
    }
  } else if ('procedural' in vol) {
    checkKnownKeys(at, vol, ['procedural', 'size']);
    checkOneOf('volume.procedural', vol.procedural, PROCEDURAL_KINDS);
    if (vol.size !== undefined)
      checkNumber('volume.size', vol.size, countUpTo(MAX_PROCEDURAL_SIZE, 'voxels per side', 2));
  } else {
    throw new VptError(
      'invalid-scene',
      `${at}: needs one of "file", "timeSeries", "raw" (with dims and type), "sidecar", "zarr", "procedural" or "channels" (one volume per channel)`,
    );
  }
}

function checkEnvironment(e: unknown): Environment {
  const env = checkObject('environment', e);
  const type = checkOneOf('environment.type', env.type, ['constant', 'latlong'] as const);
  if (type === 'constant') {
    checkKnownKeys('environment', env, ['type', 'radiance']);
    return env as unknown as Environment;
  }
  checkKnownKeys('environment', env, ['type', 'width', 'height', 'data', 'scale']);
  const width = checkNumber('environment.width', env.width, LATLONG_SIDE_RULE);
  const height = checkNumber('environment.height', env.height, LATLONG_SIDE_RULE);
  if (!Array.isArray(env.data) || env.data.length !== width * height * 3) {
    throw new VptError(
      'invalid-scene',
      `environment.data: must be an array of width*height*3 = ${width * height * 3} numbers, got ${Array.isArray(env.data) ? `${env.data.length}` : typeof env.data}`,
    );
  }
  env.data.forEach((x, i) => {
    if (typeof x !== 'number' || !Number.isFinite(x) || Math.abs(x) > FLOAT32_MAX)
      throw new VptError(
        'invalid-scene',
        `environment.data[${i}]: must be a finite float32 number, got ${JSON.stringify(x)}`,
      );
  });
  return { ...(env as object), data: Float32Array.from(env.data as number[]) } as Environment;
}

function checkLights(l: unknown): Light[] {
  if (!Array.isArray(l)) throw new VptError('invalid-scene', `lights: must be an array, got ${JSON.stringify(l)}`);
  l.forEach((light, i) => {
    const o = checkObject(`lights[${i}]`, light);
    checkKnownKeys(`lights[${i}]`, o, ['type', 'direction', 'irradiance']);
    for (const k of ['type', 'direction', 'irradiance'])
      if (o[k] === undefined) throw new VptError('invalid-scene', `lights[${i}].${k}: is required`);
  });
  return l as Light[];
}

/**
 * The scene's channel settings (core's ChannelSettings as JSON): one entry per channel of the
 * volume, each a 1D transfer function, `enabled`, an optional `color` and `range`; the rules that
 * need the loaded volume (entry count, at most 4 enabled) are core's validateChannels at setScene.
 */
function checkChannels(c: unknown, volume: unknown): void {
  if (!Array.isArray(c) || c.length < 1 || c.length > MAX_VOLUME_CHANNELS)
    throw new VptError(
      'invalid-scene',
      `channels: a list of 1 to ${MAX_VOLUME_CHANNELS} channel settings (transferFunction, enabled, color, range), got ${JSON.stringify(c)?.slice(0, 80)}`,
    );
  const listed = volumeChannelCount(volume);
  if (listed !== null && listed !== c.length)
    throw new VptError(
      'invalid-scene',
      `channels: ${c.length} entries for the ${listed} channels the volume lists (one entry per channel)`,
    );
  c.forEach((entry, i) => {
    const o = checkObject(`channels[${i}]`, entry);
    checkKnownKeys(`channels[${i}]`, o, ['transferFunction', 'enabled', 'color', 'range']);
    if (o.transferFunction === undefined)
      throw new VptError('invalid-scene', `channels[${i}].transferFunction: is required`);
    const tf = checkObject(`channels[${i}].transferFunction`, o.transferFunction);
    if (tf.dimensions !== undefined && tf.dimensions !== '1d')
      throw new VptError('invalid-scene', `channels[${i}].transferFunction: a channel takes a 1D transfer function`);
    transferFunctionFromJSON({ dimensions: '1d', ...tf });
    if (o.enabled !== undefined && typeof o.enabled !== 'boolean')
      throw new VptError(
        'invalid-scene',
        `channels[${i}].enabled: must be true or false, got ${JSON.stringify(o.enabled)}`,
      );
    if (o.color !== undefined) checkNumbers(`channels[${i}].color`, o.color, 3, { min: 0, max: 1 });
    if (o.range !== undefined) {
      const [lo, hi] = checkNumbers(`channels[${i}].range`, o.range, 2);
      if (lo === hi)
        throw new VptError('invalid-scene', `channels[${i}].range: min and max are equal (${lo}), an empty range`);
    }
  });
}

/**
 * The scene's label volume (core's SceneLabels as JSON): `volume`, one volume description of
 * integer ids (a raw file of uint8 / uint16, or any file or store whose values are integers in
 * [0, 65535]), and an optional `table` (default: every id present, palette colours); each entry
 * { id, name?, color?, opacity?, visible? }. The rules that need the loaded volumes (its dims
 * against the image's, ids against its type) are core's validateLabels at setScene.
 */
function checkLabels(l: unknown): void {
  const o = checkObject('labels', l);
  checkKnownKeys('labels', o, ['volume', 'table']);
  if (o.volume === undefined) throw new VptError('invalid-scene', 'labels.volume: is required (the label ids)');
  const v = checkObject('labels.volume', o.volume);
  if ('channels' in v) throw new VptError('invalid-scene', 'labels.volume.channels: a label volume has one channel');
  if ('procedural' in v)
    throw new VptError(
      'invalid-scene',
      'labels.volume: a label volume is a file, raw, sidecar or zarr, not procedural',
    );
  checkVolume(v, 'labels.volume');
  if (v.type !== undefined && v.type !== 'uint8' && v.type !== 'uint16')
    throw new VptError(
      'invalid-scene',
      `labels.volume.type: must be "uint8" or "uint16" (integer label ids), got ${JSON.stringify(v.type)}`,
    );
  if (o.table === undefined) return;
  if (!Array.isArray(o.table))
    throw new VptError(
      'invalid-scene',
      `labels.table: must be an array of label entries, got ${JSON.stringify(o.table)?.slice(0, 80)}`,
    );
  const ids = new Set<number>();
  o.table.forEach((entry, i) => {
    const at = `labels.table[${i}]`;
    const e = checkObject(at, entry);
    checkKnownKeys(at, e, ['id', 'name', 'color', 'opacity', 'visible']);
    if (e.id === undefined) throw new VptError('invalid-scene', `${at}.id: is required`);
    const id = checkNumber(`${at}.id`, e.id, { min: 1, max: 65535, integer: true, unit: '0 is the background' });
    if (ids.has(id)) throw new VptError('invalid-scene', `${at}.id: ${id} is listed twice`);
    ids.add(id);
    if (e.name !== undefined) checkString(`${at}.name`, e.name);
    if (e.color !== undefined) checkNumbers(`${at}.color`, e.color, 3, { min: 0, max: 1 });
    if (e.opacity !== undefined)
      checkNumber(`${at}.opacity`, e.opacity, { min: 0, max: MAX_OPACITY, unit: 'MAX_OPACITY' });
    if (e.visible !== undefined && typeof e.visible !== 'boolean')
      throw new VptError('invalid-scene', `${at}.visible: must be true or false, got ${JSON.stringify(e.visible)}`);
  });
}

/** How many channels a volume description names (a zarr's `channels`, a list of channel files), or null when only the loaded data says. */
function volumeChannelCount(v: unknown): number | null {
  if (!v || typeof v !== 'object') return null;
  const c = (v as { channels?: unknown }).channels;
  return Array.isArray(c) ? c.length : null;
}

/**
 * Validate a scene description; throws VptError ('invalid-scene', or 'limit-exceeded' for a
 * value above a limit) whose message names the field. Returns the description, typed.
 */
export function validateSceneDescription(d: unknown): SceneDescription {
  try {
    const s = checkObject('scene', d);
    checkJsonShape(s, 'scene');
    checkKnownKeys('scene', s, TOP_KEYS);
    for (const k of ['width', 'height'] as const)
      if (s[k] !== undefined) checkNumber(k, s[k], countUpTo(MAX_RENDER_SIDE, 'pixels'));
    if (s.iterations !== undefined) checkNumber('iterations', s.iterations, countUpTo(MAX_ITERATIONS));
    if (s.time !== undefined) checkNumber('time', s.time, { min: 0, max: 1e6, integer: true });
    if (s.seed !== undefined) checkNumber('seed', s.seed, { min: 0, max: 0xffffffff, integer: true });
    if (s.densityScale !== undefined)
      checkNumber('densityScale', s.densityScale, {
        min: 0,
        max: MAX_DENSITY_SCALE,
        unit: 'extinction per world unit; MAX_DENSITY_SCALE',
      });
    const renderer =
      s.renderer === undefined ? DEFAULT_RENDERER_NAME : checkOneOf('renderer', s.renderer, rendererNames());
    if (s.backend !== undefined) checkOneOf('backend', s.backend, BACKEND_NAMES);
    if (s.sampling !== undefined) checkOneOf('sampling', s.sampling, ['fast', 'exact'] as const);
    if (s.clip !== undefined) validateClip(s.clip, 'clip');
    // The rules that need the volume (the plane against its box, the window against its range) run in the page's setScene.
    if (s.slicePlane !== undefined) resolveSlicePlane(s.slicePlane, 'slicePlane');
    if (s.maxGpuBytes !== undefined)
      checkNumber('maxGpuBytes', s.maxGpuBytes, { min: 0, exclusiveMin: true, unit: 'bytes' });
    if (s.rendererParams !== undefined) {
      const params = checkObject('rendererParams', s.rendererParams);
      const check = RENDERER_PARAM_CHECKS[renderer];
      if (!check)
        throw new VptError(
          'invalid-scene',
          `rendererParams: no parameter checks for renderer "${renderer}" (add it to RENDERER_PARAM_CHECKS)`,
        );
      check(params);
    }
    if (s.volume !== undefined) checkVolume(s.volume);
    if (s.transferFunction !== undefined) {
      const tf = checkObject('transferFunction', s.transferFunction);
      transferFunctionFromJSON(tf.dimensions === undefined ? { dimensions: '1d', ...tf } : tf);
    }
    if (s.camera !== undefined) {
      const cam = checkObject('camera', s.camera);
      checkKnownKeys('camera', cam, ['position', 'target', 'up', 'fovy']);
      validateCamera({ ...defaultCamera(), ...cam } as Camera);
    }
    if (s.lights !== undefined) validateLights(checkLights(s.lights));
    if (s.environment !== undefined) validateEnvironment(checkEnvironment(s.environment));
    if (s.post !== undefined) postChainFromJSON(s.post);
    if (s.channels !== undefined) checkChannels(s.channels, s.volume);
    if (s.labels !== undefined) checkLabels(s.labels);
  } catch (e) {
    if (e instanceof VptError) throw new VptError(e.code, `Scene description: ${e.message}`, { cause: e });
    throw new VptError('invalid-scene', `Scene description: ${(e as Error).message}`, { cause: e });
  }
  return d as SceneDescription;
}
