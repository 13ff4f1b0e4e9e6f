// Files from URLs: ?src= (a height field, with its NAME.json sidecar from beside it; a TIFF
// tile by tile when its server honours Range), ?image= (an image to drape, with its world file
// from beside it) and the page's own default terrain. Fetched within the settings' time limit
// and size cap (url_fetch.js).
import { extensionOf, baseNameOf } from '../loaders/common.js';
import { worldFileCandidates } from '../geo/index.js';
import { fetchLimited, LimitError } from './url_fetch.js';
import { isTiffName, afterTilesFailed } from './tiled_open.js';

const MB = 2 ** 20;

/** Looks at a height field's or an image's answer before its body is read: an error, or a page, is neither. */
function acceptFile(response) {
  if (!response.ok) throw new Error(`HTTP ${response.status}`);
  // A server's "not found" page often comes back as 200 text/html; no height field is HTML.
  if (/text\/html/.test(response.headers.get('content-type') ?? '')) throw new Error('the server sent an HTML page');
  return true;
}

/** A sidecar is read when the server has one: a JSON answer, not its "not found" page. */
const acceptSidecar = (response) => response.ok && /json/.test(response.headers.get('content-type') ?? '');

/** A world file likewise: any answer but an error or a page (servers call .jgw many things). */
const acceptWorldFile = (response) => response.ok && !/text\/html/.test(response.headers.get('content-type') ?? '');

/** Where a fetch failed, for the status line. */
const fetchFailure = (name, url, error) =>
  `${name}: cannot fetch ${url} (${error.message}${error instanceof LimitError ? '; the limits are under Controls › Loading from a URL' : ''})`;

/**
 * @param {{ loads: import('./load_sequence.js').LoadSequence, indicator: object, settings: object,
 *   opening: ReturnType<import('./terrain_opening.js').createTerrainOpening>,
 *   drape: (image: {name: string, blob: Blob}, sidecars: { worldFile, prj, auxXml }, options?: { url?: string }) => Promise<object|null>,
 *   defaultUrlTimeoutS: number }} page
 *   settings: the page's (urlTimeout in seconds and urlMaxMB, read at each load); drape: onto
 *   the terrain on screen, null when refused; defaultUrlTimeoutS: the time limit of the page's
 *   own files (the setting's default)
 * @returns {{ openUrl, openImageUrl, openLinks }} each resolves to 'shown', 'failed' or 'cancelled'
 */
export function createUrlOpening({ loads, indicator, settings, opening, drape, defaultUrlTimeoutS }) {
  const { decode, openTiles, failed, cancelled } = opening;
  const userLimits = () => ({ timeoutMs: settings.urlTimeout * 1000, maxBytes: settings.urlMaxMB * MB });

  /**
   * Fetches [{ name, url, optional }] within `limits` ({ timeoutMs, maxBytes }) and decodes
   * them: the first is the height field, an optional one (the sidecar) is left out when its
   * server has none. `explain(error)`: a message of the caller's for a failed fetch, or null.
   */
  async function fetchAndDecode(links, limits, signal, source, quiet, explain = () => null) {
    const name = links[0].name;
    const onBytes = indicator.downloadProgress(name, quiet);
    const files = [];
    for (const link of links) {
      try {
        const bytes = await fetchLimited(link.url, link.optional ? { ...limits, signal, accept: acceptSidecar }
          : { ...limits, signal, accept: acceptFile, onBytes });
        if (bytes) files.push({ name: link.name, bytes });
      } catch (error) {
        if (signal.aborted) return cancelled(signal, name);
        if (!link.optional) return failed(explain(error) ?? fetchFailure(link.name, link.url, error));
        // A sidecar that cannot be read is one the server does not have: the file opens without it.
      }
    }
    return decode(files, {}, signal, source, quiet);
  }

  /** ?src= of a TIFF: tile by tile when the server honours Range and the file is tiled; else as afterTilesFailed says. */
  async function openUrlAsTiles(url, name, links, limits, signal) {
    try {
      return await openTiles(url, name, signal, url);
    } catch (error) {
      if (signal.aborted) return cancelled(signal, name);
      const next = afterTilesFailed(error, name, settings.tileCacheMB * MB);
      if (next.failed) return failed(next.failed);
      const { maxBytes, advice } = next.whole;
      return fetchAndDecode(links, { ...limits, maxBytes: Math.min(limits.maxBytes, maxBytes) }, signal, url, false,
        (e) => (e instanceof LimitError && /size cap/.test(e.message) ? `${name}: ${e.message}, ${advice}` : null));
    }
  }

  /** The URL `url` resolved against the page, and the name of its last path segment; throws for no URL. */
  function parse(url, fallback) {
    const parsed = new URL(url, location.href);
    const segment = parsed.pathname.split('/').pop(); // percent-encoded, as the URL has it
    return { parsed, segment, name: decodeURIComponent(segment) || fallback };
  }

  return {
    /**
     * Opens a height field at `url` (?src=) with its NAME.json sidecar from beside it (resolved
     * against the data's URL: a file on another server has its sidecar there, not on the page's).
     */
    openUrl(url) {
      return loads.run((signal) => {
        indicator.start(true);
        let target;
        try {
          target = parse(url, 'download');
        } catch (error) {
          return failed(`src=${url}: not a URL to fetch (${error.message})`);
        }
        const { parsed, segment, name } = target;
        const links = [{ name, url }];
        if (extensionOf(name) !== 'json') {
          // './' keeps a name with a colon from reading as a URL scheme.
          links.push({ name: `${baseNameOf(name)}.json`, url: new URL(`./${baseNameOf(segment)}.json`, parsed).href, optional: true });
        }
        if (isTiffName(name)) return openUrlAsTiles(url, name, links, userLimits(), signal);
        return fetchAndDecode(links, userLimits(), signal, url, false);
      });
    },

    /**
     * Drapes the image at `url` (?image=) on the terrain on screen, with its world file from
     * beside it when its server has one (x.jgw, x.jpgw or x.wld for x.jpg).
     */
    openImageUrl(url) {
      return loads.run(async (signal) => {
        indicator.start(true);
        let target;
        try {
          target = parse(url, 'image');
        } catch (error) {
          return failed(`image=${url}: not a URL to fetch (${error.message})`);
        }
        const { parsed, segment, name } = target;
        const limits = { ...userLimits(), signal };
        let bytes;
        try {
          bytes = await fetchLimited(parsed, { ...limits, accept: acceptFile, onBytes: indicator.downloadProgress(name, false) });
        } catch (error) {
          return signal.aborted ? cancelled(signal, name) : failed(fetchFailure(name, url, error));
        }
        let world = null;
        if (!/\.tiff?$/i.test(name)) {
          for (const candidate of worldFileCandidates(segment)) {
            const text = await fetchLimited(new URL(`./${candidate}`, parsed), { ...limits, maxBytes: MB, accept: acceptWorldFile }).catch(() => null);
            if (signal.aborted) return cancelled(signal, name);
            if (text) { world = { name: decodeURIComponent(candidate), blob: new Blob([text]) }; break; }
          }
        }
        if (signal.aborted) return cancelled(signal, name);
        return (await drape({ name, blob: new Blob([bytes]) }, { worldFile: world, prj: null, auxXml: null }, { url })) ? 'shown' : 'failed';
      });
    },

    /**
     * Opens files fetched from [{ name, url }] (the default terrain), with no status line of its
     * own unless it fails, and no Cancel button: the page needs a terrain. The page's own files:
     * the default time limit, and no size cap (the user's is for theirs).
     */
    openLinks(links) {
      return loads.run((signal) => {
        indicator.start(false);
        return fetchAndDecode(links, { timeoutMs: defaultUrlTimeoutS * 1000, maxBytes: Infinity }, signal, null, true);
      });
    },
  };
}
