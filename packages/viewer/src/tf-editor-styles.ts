import { css } from 'lit';

/**
 * The look both transfer-function editors share (tf-editor-1d.ts, tf-editor-2d.ts): the plot
 * frame, the form of the selected point or widget, its fields and buttons, the hint line.
 * Each editor adds its own handles, plot size and form columns after these rules.
 */
export const tfEditorStyles = css`
  :host {
    display: block;
    font: inherit;
    color: inherit;
  }
  .plot {
    position: relative;
    background: #0b0b0d;
    border: 1px solid #444;
    border-radius: 4px;
    touch-action: none;
    margin: 6px 7px;
  }
  canvas,
  svg {
    position: absolute;
    inset: 0;
    width: 100%;
    height: 100%;
    display: block;
  }
  form {
    display: grid;
    gap: 4px 6px;
    align-items: center;
    font-size: 0.85em;
  }
  input,
  select {
    min-width: 0;
    font: inherit;
    background: #1c1c20;
    color: inherit;
    border: 1px solid #555;
    border-radius: 3px;
    padding: 2px 4px;
  }
  input[type='color'] {
    padding: 0;
    height: 1.6em;
  }
  .buttons {
    display: flex;
    gap: 6px;
  }
  button {
    font: inherit;
    background: #2a2a30;
    color: inherit;
    border: 1px solid #555;
    border-radius: 3px;
    padding: 2px 8px;
    cursor: pointer;
  }
  button:focus-visible,
  input:focus-visible {
    outline: 2px solid #6af;
    outline-offset: 1px;
  }
  .hint {
    font-size: 0.8em;
    opacity: 0.7;
    margin: 0 0 4px;
  }
`;
