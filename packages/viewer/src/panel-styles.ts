import { css } from 'lit';

/**
 * The side panels' rules (panels.ts, channels.ts) and the clip handles' (drawn only with the
 * Clip panel), in the panels' lazy chunk: the element adopts them beside its own (styles.ts)
 * once that chunk is loaded, so a page without panels does not carry them.
 */
export const panelStyles = css`
  .clip-handle {
    position: absolute;
    width: 18px;
    height: 18px;
    margin: -9px 0 0 -9px;
    border-radius: 50%;
    border: 2px solid #fff;
    background: var(--vpt-accent);
    color: #fff;
    font:
      600 10px/14px system-ui,
      sans-serif;
    text-align: center;
    cursor: grab;
    touch-action: none;
    user-select: none;
    box-sizing: border-box;
    z-index: 1;
  }
  details {
    border-bottom: 1px solid #2c2c32;
  }
  summary {
    cursor: pointer;
    padding: 7px 10px;
    font-weight: 600;
    user-select: none;
  }
  .panel {
    padding: 0 10px 10px;
    display: grid;
    grid-template-columns: minmax(0, 1fr);
    gap: 6px;
  }
  .row {
    display: grid;
    grid-template-columns: 6.2rem minmax(0, 1fr);
    align-items: center;
    gap: 6px;
  }
  .row > span.value {
    font-variant-numeric: tabular-nums;
  }
  select,
  input[type='number'],
  input[type='text'] {
    background: #1c1c20;
    border: 1px solid #555;
    border-radius: 3px;
    padding: 2px 4px;
    min-width: 0;
  }
  input[type='range'] {
    min-width: 0;
    accent-color: var(--vpt-accent);
  }
  input[type='file'] {
    max-width: 100%;
  }
  input[type='color'] {
    height: 1.7em;
    padding: 0;
    border: 1px solid #555;
    background: none;
  }
  dl.readout {
    display: grid;
    grid-template-columns: auto 1fr;
    gap: 2px 10px;
    margin: 0;
    font-variant-numeric: tabular-nums;
  }
  dl.readout dt {
    opacity: 0.75;
  }
  dl.readout dd {
    margin: 0;
  }
  .buttons {
    display: flex;
    flex-wrap: wrap;
    gap: 6px;
  }
  .visually-hidden {
    position: absolute;
    width: 1px;
    height: 1px;
    overflow: hidden;
    clip: rect(0 0 0 0);
    white-space: nowrap;
  }
  .channel {
    display: grid;
    gap: 4px;
    padding: 4px 0 6px;
    border-top: 1px solid #2c2c32;
  }
  .channel .row {
    grid-template-columns: minmax(0, 1fr) auto;
  }
`;
