// Vite serves public/index.html in development and builds a static site into dist/.
// The page imports modules from web/ and shaders/ and the WASM build from build/wasm, all
// outside the root, so the project directory is allowed.
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const projectDir = fileURLToPath(new URL('.', import.meta.url));

export default defineConfig({
  root: 'public',
  base: './', // relative asset URLs: the built site works at a host's root or under any sub-path
  publicDir: false, // public/ is the root itself; assets are referenced from it directly
  server: { fs: { allow: [projectDir] }, host: '127.0.0.1' },
  build: { outDir: '../dist', emptyOutDir: true, target: 'es2022', assetsInlineLimit: 0 },
  clearScreen: false,
});
