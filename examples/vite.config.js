// Vite for a page that uses hexlod: the package is served as it is, not pre-bundled again (its
// modules are already bundled, and find the WebAssembly core, their worker and the default
// terrain beside themselves through import.meta.url, which pre-bundling would move).
import { defineConfig } from 'vite';

export default defineConfig({
  optimizeDeps: { exclude: ['hexlod'] },
});
