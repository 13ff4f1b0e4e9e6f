// Vite serves public/index.html in development and builds a static site into dist/.
// The page imports modules from web/ and shaders/ and the WASM build from build/wasm, all
// outside the root, so the project directory is allowed.
import { defineConfig } from 'vite';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { crsFilesPlugin } from './lib/crs_files_plugin.js';

const projectDir = fileURLToPath(new URL('.', import.meta.url));

// The page's Content-Security-Policy is its <meta> in public/index.html (the built site carries
// it to any static host); the dev server sends the same as a header, so development runs under
// the policy users get. Vite's client needs nothing more: its hot-reload WebSocket goes to the
// page's own host and port, which 'self' allows.
const policy = /<meta http-equiv="Content-Security-Policy" content="([^"]+)"/
  .exec(readFileSync(`${projectDir}public/index.html`, 'utf8'))?.[1];
if (!policy) throw new Error('public/index.html has no Content-Security-Policy <meta>');
const headers = { 'Content-Security-Policy': policy };

export default defineConfig({
  root: 'public',
  base: './', // relative asset URLs: the built site works at a host's root or under any sub-path
  publicDir: false, // public/ is the root itself; assets are referenced from it directly
  server: { fs: { allow: [projectDir] }, host: '127.0.0.1', headers },
  preview: { headers },
  build: { outDir: '../dist', emptyOutDir: true, target: 'es2022', assetsInlineLimit: 0 },
  // The tile workers (web/tiles/tile_worker.js) import geotiff, whose decoders load by dynamic
  // import: a worker bundle of several chunks, which only the module format allows.
  worker: { format: 'es' },
  // The EPSG definitions, one file per code (crs/CODE.json), served and built beside the page.
  plugins: [crsFilesPlugin()],
  clearScreen: false,
});
