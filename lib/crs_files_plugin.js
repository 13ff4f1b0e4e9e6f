// A vite plugin that serves the EPSG definitions to the page as one small file per code,
// crs/CODE.json beside index.html ({ code, name, proj4 }, lib/crs_definitions.js): the dev
// server answers them from the packages on disk, and the build writes every one into dist/, so
// the built site works offline from any static host (the npm package leaves dist/crs/ out, 34 MB,
// and `hexlod regress` answers them as the dev server does). The page fetches only the codes its files
// name (web/app/crs_source.js), never a list of all.
import { crsCodes, crsDefinition } from './crs_definitions.js';

/** The file's text of a code, or null when no package knows it. */
function fileOf(code) {
  const definition = crsDefinition(code);
  return definition && JSON.stringify({ code: definition.code, name: definition.name, proj4: definition.proj4 });
}

/**
 * Connect-style middleware answering crs/CODE.json from the packages: the dev server's, and the
 * static server's of `hexlod regress` in an installed package, which ships no dist/crs/.
 */
export function crsFilesMiddleware() {
  return (request, response, next) => {
    const m = /\/crs\/(\d{1,6})\.json$/.exec(new URL(request.url, 'http://localhost').pathname);
    if (!m) return next();
    const text = fileOf(Number(m[1]));
    response.statusCode = text ? 200 : 404;
    response.setHeader('Content-Type', text ? 'application/json' : 'text/plain');
    response.end(text ?? 'no such EPSG code');
  };
}

export function crsFilesPlugin() {
  return {
    name: 'hexlod-crs-files',
    configureServer(server) {
      server.middlewares.use(crsFilesMiddleware());
    },
    generateBundle() {
      for (const code of crsCodes()) {
        const text = fileOf(code);
        if (text) this.emitFile({ type: 'asset', fileName: `crs/${code}.json`, source: text });
      }
    },
  };
}
