#!/usr/bin/env python3
"""
Reference images for the MCRT renderer from an independent renderer: Mitsuba 3
(PyPI `mitsuba`, variant scalar_rgb, integrator volpath, Russian roulette off).

Each scene is described once, in vpt's scene-description JSON (what `vpt-render` and the
headless page read), written next to the images; this script builds the same scene in
Mitsuba following docs/design.md's conventions:

  * box: the volume fills [-0.5, 0.5]^3 (cubic volumes only here); Mitsuba's `cube`
    ([-1, 1]^3) scaled by 0.5 with a null BSDF bounds the medium;
  * sampling: a `gridvolume` with trilinear filtering and clamp wrap, mapped from [0, 1]^3
    to the box (Dr.Jit textures are cell-centred, like GL LINEAR + CLAMP_TO_EDGE);
  * extinction: sigma_t = densityScale * opacity(value); the scenes use a linear ramp
    transfer function (opacity = value, which vpt's 256-texel rasterization reproduces
    exactly) and one constant colour, so Mitsuba's sigma_t grid is the volume itself
    scaled by densityScale and its albedo that colour;
  * camera: `perspective`, fov_axis y, look_at(position, target, up), box pixel filter
    (checked below against docs/design.md's ray formula);
  * Henyey-Greenstein `hg` with the same g (both: g > 0 forward);
  * lights: `constant` environment radiance, `directional` with irradiance E and
    direction = -(vpt's direction toward the light);
  * depth: vpt's single scattering (one real scattering event) = Mitsuba max_depth 2;
    multiple scattering with unlimited depth = max_depth -1; rr_depth beyond any path.

Output per scene (benchmarks/reference/): <name>.json (the vpt scene description plus the
reference metadata), <name>-mean.pfm and <name>-stderr.pfm (per-pixel mean of `runs`
independent renders of `spp` samples each, and the standard error of that mean).

Usage: pip install mitsuba numpy && python3 benchmarks/reference/make_reference.py
"""
import json
import math
import os
import struct
import sys
import time

import numpy as np
import mitsuba as mi

mi.set_variant('scalar_rgb')
HERE = os.path.dirname(os.path.abspath(__file__))

SCENES = {
    # Multiple scattering, unlimited depth: a Gaussian blob with coloured albedo, forward
    # scattering, lit by a directional light and a constant sky.
    'mitsuba-blob-multiple': {
        'width': 16, 'height': 16, 'renderer': 'mcrt',
        'rendererParams': {'scattering': 'multiple', 'maxDepth': -1, 'anisotropy': 0.4},
        'volume': {'procedural': 'blob', 'size': 16},
        'transferFunction': {'dimensions': '1d', 'points': [
            {'value': 0, 'color': [0.9, 0.7, 0.5], 'opacity': 0},
            {'value': 1, 'color': [0.9, 0.7, 0.5], 'opacity': 1}]},
        'camera': {'position': [0.4, 0.6, 1.9], 'target': [0, 0, 0], 'up': [0, 1, 0], 'fovy': 0.62},
        'lights': [{'type': 'directional', 'direction': [1, 1.5, 0.5], 'irradiance': [2.5, 2.2, 1.8]}],
        'environment': {'type': 'constant', 'radiance': [0.6, 0.7, 0.9]},
        'densityScale': 12,
    },
    # Single scattering (max_depth 2): a linear ramp along x (heterogeneous), back-scattering
    # phase function, directional light and a dim sky.
    'mitsuba-ramp-single': {
        'width': 16, 'height': 16, 'renderer': 'mcrt',
        'rendererParams': {'scattering': 'single', 'anisotropy': -0.3},
        'volume': {'procedural': 'ramp', 'size': 16},
        'transferFunction': {'dimensions': '1d', 'points': [
            {'value': 0, 'color': [0.95, 0.8, 0.6], 'opacity': 0},
            {'value': 1, 'color': [0.95, 0.8, 0.6], 'opacity': 1}]},
        'camera': {'position': [-0.8, 0.5, 1.8], 'target': [0, 0, 0], 'up': [0, 1, 0], 'fovy': 0.7},
        'lights': [{'type': 'directional', 'direction': [-0.6, 0.8, 1.0], 'irradiance': [3, 3, 3]}],
        'environment': {'type': 'constant', 'radiance': [0.15, 0.2, 0.3]},
        'densityScale': 6,
    },
    # An inverted value range (issue 12): vpt renders the blob stored as int16
    # x = round(15000 - 30000 v) with valueRange [15000, -15000] (dense matter dark, LO > HI);
    # Mitsuba gets the range pre-applied, (x - 15000) / (-15000 - 15000), as its grid.
    'mitsuba-blob-inverted': {
        'width': 16, 'height': 16, 'renderer': 'mcrt',
        'rendererParams': {'scattering': 'multiple', 'maxDepth': -1, 'anisotropy': 0.2},
        'volume': {'procedural': 'blob', 'size': 16},
        'invertedStorage': {'type': 'int16', 'valueRange': [15000, -15000]},
        'transferFunction': {'dimensions': '1d', 'points': [
            {'value': 0, 'color': [0.7, 0.85, 0.9], 'opacity': 0},
            {'value': 1, 'color': [0.7, 0.85, 0.9], 'opacity': 1}]},
        'camera': {'position': [-0.5, 0.7, 1.8], 'target': [0, 0, 0], 'up': [0, 1, 0], 'fovy': 0.62},
        'lights': [{'type': 'directional', 'direction': [0.8, 1.2, 0.6], 'irradiance': [2.5, 2.4, 2.2]}],
        'environment': {'type': 'constant', 'radiance': [0.5, 0.55, 0.6]},
        'densityScale': 12,
    },
}


def procedural(kind, n):
    """core's createProceduralVolume (scene/procedural.ts), as float32 [z, y, x]."""
    c = (np.arange(n) + 0.5) / n - 0.5
    z, y, x = np.meshgrid(c, c, c, indexing='ij')
    if kind == 'blob':
        r2 = x * x + y * y + z * z
        v = np.exp(-r2 / (2 * 0.18 * 0.18))
    elif kind == 'ramp':
        v = np.broadcast_to((np.arange(n) / (n - 1))[None, None, :], (n, n, n))
    else:
        raise ValueError(kind)
    return np.ascontiguousarray(v, dtype=np.float32)


def check_camera(sensor, cam, W, H):
    """Mitsuba's rays must be docs/design.md's: f + (2x-1) tan(fovy/2) (W/H) r + (1-2y) tan(fovy/2) u."""
    f = np.subtract(cam['target'], cam['position'], dtype=float); f /= np.linalg.norm(f)
    r = np.cross(f, cam['up']); r /= np.linalg.norm(r)
    u = np.cross(r, f)
    t = math.tan(cam['fovy'] / 2)
    for fx, fy in [(0, 0), (1, 0), (0.3, 0.8), (1, 1)]:
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f(fx, fy), mi.Point2f(0.5, 0.5))
        d = f + (2 * fx - 1) * t * (W / H) * r + (1 - 2 * fy) * t * u
        d /= np.linalg.norm(d)
        assert np.allclose(np.array(ray.d), d, atol=1e-5), (fx, fy, np.array(ray.d), d)


def mitsuba_scene(desc):
    pts = desc['transferFunction']['points']
    assert len(pts) == 2 and pts[0]['value'] == 0 and pts[0]['opacity'] == 0 and pts[1]['value'] == 1 and pts[1]['opacity'] == 1 and pts[0]['color'] == pts[1]['color'], 'ramp TF only'
    vol = desc['volume']
    grid = procedural(vol['procedural'], vol['size'])
    inv = desc.get('invertedStorage')
    if inv:
        # The values vpt stores (int16) and then maps through the inverted range, pre-applied here.
        lo, hi = inv['valueRange']
        stored = np.round(lo + (hi - lo) * grid.astype(np.float64)).astype(np.int16)
        grid = np.clip((stored.astype(np.float64) - lo) / (hi - lo), 0, 1).astype(np.float32)
    grid = grid[..., None]
    params = desc['rendererParams']
    cam = desc['camera']
    to_box = mi.ScalarTransform4f().translate([-0.5, -0.5, -0.5])
    medium = {
        'type': 'heterogeneous',
        'sigma_t': {'type': 'gridvolume', 'grid': mi.VolumeGrid(grid), 'filter_type': 'trilinear', 'wrap_mode': 'clamp', 'to_world': to_box},
        'albedo': {'type': 'rgb', 'value': pts[0]['color']},
        'scale': float(desc['densityScale']),
        'phase': {'type': 'hg', 'g': float(params.get('anisotropy', 0))},
    }
    single = params.get('scattering') == 'single'
    scene = {
        'type': 'scene',
        'integrator': {'type': 'volpath', 'max_depth': 2 if single else -1, 'rr_depth': 1 << 30},
        'sensor': {
            'type': 'perspective', 'fov_axis': 'y', 'fov': math.degrees(cam['fovy']),
            'to_world': mi.ScalarTransform4f().look_at(origin=cam['position'], target=cam['target'], up=cam['up']),
            'film': {'type': 'hdrfilm', 'width': desc['width'], 'height': desc['height'], 'rfilter': {'type': 'box'}, 'pixel_format': 'rgb'},
            'sampler': {'type': 'independent'},
        },
        'box': {'type': 'cube', 'to_world': mi.ScalarTransform4f().scale(0.5), 'bsdf': {'type': 'null'}, 'interior': medium},
        'sky': {'type': 'constant', 'radiance': {'type': 'rgb', 'value': desc['environment']['radiance']}},
    }
    for i, l in enumerate(desc.get('lights', [])):
        d = np.asarray(l['direction'], float)
        d = -d / np.linalg.norm(d)
        scene[f'sun{i}'] = {'type': 'directional', 'direction': d.tolist(), 'irradiance': {'type': 'rgb', 'value': l['irradiance']}}
    return scene


def write_pfm(path, rgb):
    """rgb: float32 [H, W, 3], row 0 at the top; PFM stores rows bottom to top, little-endian."""
    h, w, _ = rgb.shape
    with open(path, 'wb') as f:
        f.write(f'PF\n{w} {h}\n-1.0\n'.encode('ascii'))
        f.write(np.ascontiguousarray(rgb[::-1], dtype='<f4').tobytes())


def main():
    spp = int(os.environ.get('SPP', 1024))
    runs = int(os.environ.get('RUNS', 16))
    only = sys.argv[1:]
    for name, desc in SCENES.items():
        if only and name not in only:
            continue
        scene = mi.load_dict(mitsuba_scene(desc))
        check_camera(scene.sensors()[0], desc['camera'], desc['width'], desc['height'])
        t0 = time.time()
        imgs = np.stack([np.array(mi.render(scene, spp=spp, seed=1000 + k), dtype=np.float64) for k in range(runs)])
        mean = imgs.mean(axis=0)
        stderr = imgs.std(axis=0, ddof=1) / math.sqrt(runs)
        write_pfm(os.path.join(HERE, f'{name}-mean.pfm'), mean.astype(np.float32))
        write_pfm(os.path.join(HERE, f'{name}-stderr.pfm'), stderr.astype(np.float32))
        meta = dict(desc, reference={
            'renderer': f'Mitsuba {mi.__version__}', 'variant': 'scalar_rgb', 'integrator': 'volpath',
            'max_depth': 2 if desc['rendererParams'].get('scattering') == 'single' else -1, 'rr_depth': 1 << 30,
            'spp': spp, 'runs': runs, 'seconds': round(time.time() - t0, 1),
            'mean': f'{name}-mean.pfm', 'stderr': f'{name}-stderr.pfm',
            'note': 'stderr is the standard error of the mean over the independent runs (runs - 1 degrees of freedom)',
        })
        with open(os.path.join(HERE, f'{name}.json'), 'w') as f:
            json.dump(meta, f, indent=1)
        print(f'{name}: {runs} x {spp} spp in {time.time() - t0:.1f} s, mean {mean.mean():.4f}, median stderr {np.median(stderr):.2e}')


if __name__ == '__main__':
    main()
