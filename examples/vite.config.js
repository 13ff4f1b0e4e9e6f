// Vite for a page that uses hexlod: its modules are served as they are, through Vite's own
// pipeline (they import shaders as text and locate the WebAssembly core and their worker beside
// themselves), and only its CommonJS dependencies are pre-bundled.
import { defineConfig } from 'vite';

export default defineConfig({
  optimizeDeps: { exclude: ['hexlod'], include: ['hexlod > proj4', 'hexlod > proj4-list', 'hexlod > epsg-index'] },
  worker: { format: 'es' },
});
