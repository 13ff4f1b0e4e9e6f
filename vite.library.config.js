// The package's browser library (what `import 'hexlod'` and `import 'hexlod/element'` load):
// the JS API bundled into library/ with its npm dependencies and its shaders, as plain ES modules
// that need no bundler (a <script type="module"> with an import map loads them) and that any
// bundler takes as they are. The WebAssembly core, the tile worker and the default terrain are
// files beside them, found through import.meta.url; the terrain is fetched only when shown.
// Not Vite's library mode: it inlines every asset as base64, which would put the terrain and
// the core into the script.
import { defineConfig } from 'vite';

export default defineConfig({
  base: './', // assets are found beside the modules (import.meta.url), wherever the package is served
  publicDir: false,
  build: {
    outDir: 'library',
    emptyOutDir: true,
    target: 'es2022',
    assetsInlineLimit: 0,
    copyPublicDir: false,
    rollupOptions: {
      input: { hexlod: 'web/api/index.js', element: 'web/api/element.js' },
      preserveEntrySignatures: 'exports-only', // the entries keep their exports: they are a library
      output: { entryFileNames: '[name].js', chunkFileNames: 'chunks/[name]-[hash].js', assetFileNames: 'assets/[name]-[hash][extname]' },
    },
  },
  worker: { format: 'es' },
  logLevel: 'warn',
});
