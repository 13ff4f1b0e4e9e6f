// A file the page fetches whole by its address (a flight's files, an overlay by ?overlay=), named
// as a dropped file is: the last part of its path.

/** The file name an address ends with, decoded ('my track.gpx'), or the address itself. */
export function fileNameOf(url) {
  return decodeURIComponent(new URL(url, location.href).pathname.split('/').pop() || url);
}

/**
 * @param {string} url
 * @returns {Promise<{name: string, bytes: Uint8Array}>}
 * @throws {Error} the network's message, or 'HTTP 404 Not Found'
 */
export async function fetchFile(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`.trim());
  return { name: fileNameOf(url), bytes: new Uint8Array(await response.arrayBuffer()) };
}
