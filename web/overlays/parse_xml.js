// XML for the overlays' GPX and KML. fast-xml-parser's validator checks the document first and
// says where it breaks (line and column); only a well-formed document reaches a DOM parser, the
// browser's own in the page (fast) or @xmldom/xmldom in Node (loaded only there). The browser
// would otherwise build an error document whose inline styles the page's Content-Security-
// Policy refuses, with nothing useful to tell the person.
import { XMLValidator } from 'fast-xml-parser';
import { OverlayError } from './overlay_error.js';

/**
 * @param {string} text
 * @returns {Promise<Document>}
 * @throws {OverlayError} a malformed document
 */
export async function parseXml(text) {
  const verdict = XMLValidator.validate(text);
  if (verdict !== true) {
    const { msg, line, col } = verdict.err;
    // The validator names tags left open at the end as a list: a file cut short, most often.
    const open = /^Invalid '(\[.*\])' found/s.exec(msg);
    if (open) {
      const tags = JSON.parse(open[1]).map((tag) => `<${tag}>`).join(', ');
      throw new OverlayError(`malformed XML: the document ends with ${tags} still open (a file cut short?)`);
    }
    throw new OverlayError(`malformed XML at line ${line}, column ${col}: ${msg}`);
  }
  if (typeof globalThis.DOMParser === 'function') return new globalThis.DOMParser().parseFromString(text, 'application/xml');
  const { DOMParser } = await import('@xmldom/xmldom');
  let problem = null;
  const parser = new DOMParser({
    onError: (level, message) => {
      if (level === 'warning') return;
      problem ??= String(message).replace(/\s+/g, ' ').trim();
      throw new OverlayError(`malformed XML: ${problem}`);
    },
  });
  try {
    return parser.parseFromString(text, 'text/xml');
  } catch (error) {
    throw new OverlayError(problem ? `malformed XML: ${problem.slice(0, 200)}` : `malformed XML: ${error.message}`);
  }
}
