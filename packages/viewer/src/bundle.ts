/**
 * Entry of dist/vpt-viewer.bundle.js, the one-file build for plain HTML pages:
 *   <script type="module" src=".../vpt-viewer.bundle.js"></script>
 *   <vpt-viewer src="head.json" renderer="eam"></vpt-viewer>
 * It contains Lit, the used parts of Three.js, core, post and every installed renderer,
 * and re-exports core and post for pages that build scenes in code (less their CPU reference
 * twins: bundle-core.ts, bundle-post.ts).
 */
export * from './index.js';
export * as core from './bundle-core.js';
export * as post from './bundle-post.js';
