import { css } from 'lit';

/** The element's look: dark, compact, a visible focus ring on everything that takes focus. */
export const viewerStyles = css`
  :host {
    display: block;
    position: relative;
    height: 480px;
    box-sizing: border-box;
    font:
      13px/1.35 system-ui,
      sans-serif;
    color: #ddd;
    background: #000;
    container-type: inline-size;
    --vpt-accent: #6af;
    --vpt-panel-bg: #16161a;
    --vpt-panel-width: 19rem;
  }
  :host([hidden]) {
    display: none;
  }
  .layout {
    display: flex;
    width: 100%;
    height: 100%;
  }
  .view {
    position: relative;
    flex: 1 1 auto;
    min-width: 0;
    overflow: hidden;
  }
  .panes {
    flex: 1 1 auto;
    min-width: 0;
    display: grid;
    grid-template: 1fr / 1fr;
    gap: 2px;
    background: #222;
  }
  .panes[data-layout='slices'] {
    grid-template: 1fr / repeat(3, minmax(0, 1fr));
  }
  .panes[data-layout='slices'] .view {
    display: none;
  }
  /* Quad: axial and coronal above, sagittal and the 3D view below. */
  .panes[data-layout='quad'] {
    grid-template: repeat(2, minmax(0, 1fr)) / repeat(2, minmax(0, 1fr));
  }
  .panes[data-layout='quad'] .view {
    grid-area: 2 / 2;
  }
  /* Narrow (a phone): the panes stack, each a share of the height. */
  .layout.narrow .panes[data-layout='slices'] {
    grid-template: repeat(3, minmax(0, 1fr)) / minmax(0, 1fr);
  }
  .layout.narrow .panes[data-layout='quad'] {
    grid-template: repeat(4, minmax(0, 1fr)) / minmax(0, 1fr);
  }
  .layout.narrow .panes[data-layout='quad'] .view {
    grid-area: 4 / 1;
  }
  .view,
  .pane {
    min-height: 0;
  }
  .pane {
    position: relative;
    overflow: hidden;
    background: #000;
    display: flex;
    align-items: center;
    justify-content: center;
    padding-bottom: 18px;
    box-sizing: border-box;
  }
  .stage {
    position: relative;
    touch-action: none;
    cursor: crosshair;
    user-select: none;
  }
  .stage canvas {
    position: absolute;
    left: 0;
    top: 0;
    display: block;
    transform-origin: 0 0;
  }
  .cross-v,
  .cross-h {
    position: absolute;
    background: rgb(255 200 0 / 0.7);
    pointer-events: none;
  }
  .cross-v {
    top: 0;
    bottom: 0;
    width: 1px;
  }
  .cross-h {
    left: 0;
    right: 0;
    height: 1px;
  }
  .orient {
    position: absolute;
    color: #fc6;
    font-weight: 600;
    pointer-events: none;
    text-shadow: 0 0 2px #000;
  }
  .orient.top {
    top: 2px;
    left: 50%;
  }
  .orient.bottom {
    bottom: 2px;
    left: 50%;
  }
  .orient.left {
    left: 3px;
    top: 50%;
  }
  .orient.right {
    right: 3px;
    top: 50%;
  }
  .pane-title,
  .probe {
    position: absolute;
    bottom: 0;
    margin: 0;
    font-size: 11px;
    line-height: 18px;
    white-space: nowrap;
  }
  .pane-title {
    left: 6px;
    color: #aaa;
  }
  .probe {
    right: 6px;
    color: #fff;
  }
  .view canvas {
    position: absolute;
    inset: 0;
    width: 100%;
    height: 100%;
    display: block;
    touch-action: none;
    outline: none;
  }
  .view canvas.still {
    pointer-events: none;
  }
  .view canvas:focus-visible {
    box-shadow: inset 0 0 0 2px var(--vpt-accent);
  }
  .overlay {
    position: absolute;
    left: 0;
    right: 0;
    margin: 0;
    padding: 6px 10px;
    font-size: 12px;
  }
  .status {
    top: 0;
    background: #000a;
    pointer-events: none;
  }
  .error {
    bottom: 0;
    background: #7a1010ee;
    color: #fff;
    display: flex;
    gap: 8px;
    align-items: flex-start;
  }
  .error p {
    margin: 0;
    flex: 1;
    white-space: pre-wrap;
    overflow-wrap: anywhere;
  }
  .lost {
    inset: 0;
    display: grid;
    place-content: center;
    gap: 8px;
    text-align: center;
    background: #000c;
  }
  .toolbar {
    position: absolute;
    top: 6px;
    right: 6px;
    display: flex;
    flex-wrap: wrap;
    justify-content: flex-end;
    max-width: calc(100% - 12px);
    gap: 4px;
  }
  .drop {
    position: absolute;
    inset: 0;
    border: 3px dashed var(--vpt-accent);
    background: #0468;
    display: grid;
    place-content: center;
    pointer-events: none;
  }
  button,
  select,
  input {
    font: inherit;
    color: inherit;
  }
  button {
    background: #2a2a30e6;
    border: 1px solid #555;
    border-radius: 4px;
    padding: 3px 9px;
    cursor: pointer;
  }
  button:hover {
    background: #3a3a42;
  }
  button:focus-visible,
  select:focus-visible,
  input:focus-visible,
  summary:focus-visible {
    outline: 2px solid var(--vpt-accent);
    outline-offset: 1px;
  }
  aside {
    flex: 0 0 var(--vpt-panel-width);
    max-width: 100%;
    overflow-y: auto;
    background: var(--vpt-panel-bg);
    border-left: 1px solid #333;
    box-sizing: border-box;
  }
  /* Narrow (set by the element from its width): the panels are an overlay over the image, opened by the toolbar button. */
  .layout.narrow aside {
    position: absolute;
    inset: 0;
    z-index: 2;
    border-left: 0;
    padding-top: 34px;
    flex: none;
  }
  .toolbar {
    z-index: 3;
  }
  .toolbar button {
    font-size: 12px;
  }
  .stats-line {
    position: absolute;
    left: 0;
    bottom: 3px;
    margin: 0;
    padding: 2px 6px;
    max-width: calc(100% - 12px);
    box-sizing: border-box;
    font-size: 11px;
    font-variant-numeric: tabular-nums;
    color: #e8e8e8;
    background: #000a;
    border-top-right-radius: 4px;
    white-space: nowrap;
    overflow: hidden;
    text-overflow: ellipsis;
    pointer-events: none;
  }
  .progress {
    position: absolute;
    left: 0;
    right: 0;
    bottom: 0;
    height: 3px;
    background: #fff2;
    pointer-events: none;
  }
  .progress > div {
    height: 100%;
    background: var(--vpt-accent);
    transition: width 0.2s linear;
  }
  .progress.indeterminate > div {
    opacity: 0.5;
    animation: vpt-pulse 1s ease-in-out infinite alternate;
  }
  @keyframes vpt-pulse {
    from {
      opacity: 0.2;
    }
    to {
      opacity: 0.8;
    }
  }
  @media (pointer: coarse) {
    button {
      min-height: 32px;
      min-width: 32px;
    }
  }
`;
