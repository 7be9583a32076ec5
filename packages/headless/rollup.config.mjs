import { libraryConfig } from '../../rollup.lib.mjs';

// Node entry points (library, CLIs) and the in-browser page module, which the
// page/index.html import map loads next to the other packages' dist/.
export default libraryConfig({
  input: {
    index: 'src/index.ts',
    'cli/render': 'src/cli/render.ts',
    'cli/serve': 'src/cli/serve.ts',
    'page/vpt-page': 'src/page/vpt-page.ts',
  },
});
