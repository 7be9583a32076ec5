/**
 * What the side panels (panels.ts) read and write of the element that shows them: its
 * attributes as properties, the state they display, and the few actions they start. The
 * `<vpt-viewer>` element implements it; the panels import this interface, never the element,
 * so the two modules do not import each other.
 */
import type { Clip, Light, Renderer, TransferFunction } from '@vpt/core';
import type { ToneMapOperator } from '@vpt/post';
import type { BackendName, EnvironmentValue } from './attributes.js';
import type { GradientSamples, Histogram1D } from './histogram.js';
import type { LoadedVolumeLike, ViewerChannel, VolumeSource } from './loading/types.js';
import type { RefinementStats } from './session.js';

/** The panels, in their order (the `panels` attribute names a subset). */
export const PANEL_NAMES = ['tf', 'channels', 'lights', 'clip', 'labels', 'quality', 'stats', 'export'] as const;
export type PanelName = (typeof PANEL_NAMES)[number];

/** The properties a panel control may set, each through PanelHost.setInternal. */
export type InternalProperty =
  | 'camera'
  | 'clip'
  | 'transferFunction'
  | 'lights'
  | 'environment'
  | 'renderer'
  | 'backend'
  | 'exposure'
  | 'toneMapper'
  | 'maxSamples'
  | 'targetError'
  | 'densityScale'
  | 'seed'
  | 'rendererParams'
  | 'resolutionScale'
  | 'channels'
  | 'labelTable';

/** The state the panels display, with the defaults of unset attributes filled in. */
export interface PanelState {
  transferFunction: TransferFunction;
  histogram: Histogram1D | null;
  lights: Light[];
  environment: EnvironmentValue;
  densityScale: number;
  stats: RefinementStats | null;
  backendKind: string | null;
  volume: LoadedVolumeLike | null;
  rendererInstance: Renderer | null;
}

export interface PanelHost {
  readonly renderer: string;
  readonly backend: BackendName;
  readonly rendererParams: Record<string, unknown> | string | null;
  readonly exposure: number;
  readonly toneMapper: ToneMapOperator;
  readonly maxSamples: number;
  readonly targetError: number;
  readonly resolutionScale: number;
  readonly seed: number;
  /** The clip planes and crop box (null: nothing cut); the Clip panel edits it. */
  readonly clip: Clip | string | null;
  /** Each channel's settings of a multichannel volume (null: one channel); the Channels panel edits them. */
  readonly channels: ViewerChannel[] | null;
  readonly converged: boolean;
  readonly panelState: PanelState;
  /** The Labels panel (labels-layer.ts, loaded with a label volume), or nothing without one. */
  labelsPanel(): unknown;
  /** The core 2D preset the transfer function was fitted from, if any. */
  readonly fittedPresetName: string | null;
  /** The volume's (value, gradient) pairs for the 2D editor's histogram. */
  gradientSamples(): GradientSamples | null;
  /** Set a property as the user did: reflected, and announced with `vpt-change`. */
  setInternal(property: InternalProperty, value: unknown): void;
  load(source: VolumeSource): Promise<void>;
  resetCamera(): void;
  downloadScreenshot(): Promise<void>;
  downloadHDR(format: 'pfm' | 'exr'): Promise<void>;
}
