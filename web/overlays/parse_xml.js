// XML for the overlays' GPX and KML: the browser's DOMParser in the page, @xmldom/xmldom in Node
// (loaded only there), each made to refuse a malformed document with the parser's own words
// (the browser marks one with a <parsererror> element instead of throwing).
import { OverlayError } from './overlay_error.js';

/**
 * @param {string} text
 * @returns {Promise<Document>}
 * @throws {OverlayError} a malformed document
 */
export async function parseXml(text) {
  if (typeof globalThis.DOMParser === 'function') {
    const doc = new globalThis.DOMParser().parseFromString(text, 'application/xml');
    const error = doc.getElementsByTagName('parsererror')[0];
    if (error) throw new OverlayError(`malformed XML: ${error.textContent.replace(/\s+/g, ' ').trim().slice(0, 200)}`);
    return doc;
  }
  const { DOMParser } = await import('@xmldom/xmldom');
  let problem = null;
  const parser = new DOMParser({
    onError: (level, message) => {
      if (level !== 'warning') {
        problem ??= String(message).replace(/\s+/g, ' ').trim();
        throw new OverlayError(`malformed XML: ${problem}`);
      }
    },
  });
  try {
    return parser.parseFromString(text, 'text/xml');
  } catch (error) {
    throw new OverlayError(problem ? `malformed XML: ${problem.slice(0, 200)}` : `malformed XML: ${error.message}`);
  }
}
