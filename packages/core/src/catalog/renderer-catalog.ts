/**
 * The renderers of this repository, named once: every page, registry and helper that
 * turns a renderer name into a renderer (the headless page, the viewer's registry, the
 * benchmark page, the test pages) reads this table and imports the package by its name
 * when first used. Core does not depend on the renderer packages: the table is plain data
 * and the import happens in the caller's module graph (an import map, a bundler, Node).
 *
 * Adding a renderer: one entry here, plus the workspace plumbing listed in
 * docs/architecture.md, "How to add a renderer".
 */

/**
 * A renderer parameter a user interface offers. `undefined` in the parameter object
 * means the renderer's own default. `read`/`write` reach into nested parameters (the
 * first isosurface's value, say); without them the parameter is `params[name]`.
 */
export interface RendererParamSpec {
  name: string;
  label: string;
  kind?: 'number' | 'select' | 'boolean' | 'color';
  min?: number;
  max?: number;
  step?: number;
  options?: readonly string[];
  /** Shown next to an empty field (the renderer's default, in words). */
  placeholder?: string;
  /** The renderer's default, shown by boolean and select controls when the parameter is unset. */
  defaultValue?: unknown;
  read?(params: Record<string, unknown>): unknown;
  write?(params: Record<string, unknown>, value: unknown): Record<string, unknown>;
}

export interface RendererCatalogEntry {
  /** The name scenes, attributes and configurations use (`renderer: 'mcrt'`). */
  readonly name: string;
  /** Shown in user interfaces. */
  readonly label: string;
  /** The npm package that provides it. */
  readonly packageName: string;
  /** The package's export: a class constructed with the parameter object. */
  readonly exportName: string;
  /** The parameters a user interface offers. */
  readonly params: readonly RendererParamSpec[];
}

const step = (placeholder: string): RendererParamSpec => ({
  name: 'stepSize',
  label: 'Step size',
  min: 0.0005,
  max: 0.05,
  step: 0.0005,
  placeholder,
});

/** The first isosurface's fields, edited in place (the iso renderer takes a list of surfaces). */
type Surface = { value: number; color: [number, number, number]; opacity?: number };
const DEFAULT_SURFACE: Surface = { value: 0.5, color: [1, 1, 1], opacity: 1 };
const firstSurface = (p: Record<string, unknown>): Surface =>
  (p.surfaces as Surface[] | undefined)?.[0] ?? DEFAULT_SURFACE;
const withFirstSurface = (p: Record<string, unknown>, patch: Partial<Surface>) => {
  const surfaces = [...((p.surfaces as Surface[] | undefined) ?? [DEFAULT_SURFACE])];
  surfaces[0] = { ...surfaces[0], ...patch };
  return { ...p, surfaces };
};

export const RENDERER_CATALOG: readonly RendererCatalogEntry[] = [
  {
    name: 'mip',
    label: 'Maximum intensity',
    packageName: '@vpt/renderer-mip',
    exportName: 'MipRenderer',
    params: [step('half a voxel')],
  },
  {
    name: 'iso',
    label: 'Isosurface',
    packageName: '@vpt/renderer-iso',
    exportName: 'IsoRenderer',
    params: [
      {
        name: 'isoValue',
        label: 'Iso value',
        min: 0,
        max: 1,
        step: 0.01,
        placeholder: '0.5',
        read: (p) => firstSurface(p).value,
        write: (p, v) => withFirstSurface(p, { value: v as number }),
      },
      {
        name: 'isoColor',
        label: 'Surface colour',
        kind: 'color',
        read: (p) => firstSurface(p).color,
        write: (p, v) => withFirstSurface(p, { color: v as Surface['color'] }),
      },
      step('half a voxel'),
      { name: 'specular', label: 'Specular', min: 0, max: 1, step: 0.05, placeholder: '0.1' },
      { name: 'shininess', label: 'Shininess', min: 1, max: 1000, step: 1, placeholder: '40' },
      { name: 'shadows', label: 'Shadows', kind: 'boolean', defaultValue: true },
      { name: 'ambientOcclusion', label: 'Ambient occlusion', kind: 'boolean', defaultValue: true },
    ],
  },
  {
    name: 'eam',
    label: 'Emission–absorption',
    packageName: '@vpt/renderer-eam',
    exportName: 'EamRenderer',
    params: [
      step('one voxel'),
      { name: 'cutoff', label: 'Early-exit transmittance', min: 0, max: 0.1, step: 0.0001, placeholder: '1e-6' },
    ],
  },
  {
    name: 'mcrt',
    label: 'Path tracing (MCRT)',
    packageName: '@vpt/renderer-mcrt',
    exportName: 'McrtRenderer',
    params: [
      {
        name: 'scattering',
        label: 'Scattering',
        kind: 'select',
        options: ['multiple', 'single'],
        defaultValue: 'multiple',
      },
      { name: 'anisotropy', label: 'Anisotropy g', min: -0.99, max: 0.99, step: 0.05, placeholder: '0' },
      { name: 'maxDepth', label: 'Max bounces', min: -1, max: 256, step: 1, placeholder: 'unlimited' },
      {
        name: 'tracking',
        label: 'Shadow tracking',
        kind: 'select',
        options: ['auto', 'residual', 'ratio', 'delta'],
        defaultValue: 'auto',
      },
      {
        name: 'environmentSampling',
        label: 'Environment sampling',
        kind: 'select',
        options: ['auto', 'mis', 'light', 'phase'],
        defaultValue: 'auto',
      },
      { name: 'majorantGrid', label: 'Majorant grid', kind: 'boolean', defaultValue: true },
    ],
  },
  {
    // The parameters' one definition is SLICE_PARAM_TABLE in @vpt/renderer-slice (core cannot import it);
    // the window ([center, width] in data units) is set through renderer-params.
    name: 'slice',
    label: 'Slice',
    packageName: '@vpt/renderer-slice',
    exportName: 'SliceRenderer',
    params: [
      { name: 'axis', label: 'Axis', kind: 'select', options: ['x', 'y', 'z'], defaultValue: 'z' },
      { name: 'index', label: 'Slice index', min: 0, max: 2047, step: 1, placeholder: 'the middle slice' },
      { name: 'sampling', label: 'Sampling', kind: 'select', options: ['nearest', 'linear'], defaultValue: 'nearest' },
      {
        name: 'colormap',
        label: 'Colour map',
        kind: 'select',
        options: ['grey', 'viridis', 'hot', 'coolwarm', 'transfer-function'],
        defaultValue: 'grey',
      },
      { name: 'fit', label: 'Fit to image', kind: 'boolean', defaultValue: false },
    ],
  },
];

/** The catalog entry of a renderer name, or undefined. */
export function rendererCatalogEntry(name: string): RendererCatalogEntry | undefined {
  return RENDERER_CATALOG.find((e) => e.name === name);
}

/** The renderer names of the catalog, for error messages ("eam, mip, …"). */
export function rendererNames(): string[] {
  return RENDERER_CATALOG.map((e) => e.name);
}
