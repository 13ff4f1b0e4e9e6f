// Comparisons and reports of `hexlod regress`: per-frame figures exactly, pixels with a
// tolerance (a per-pixel threshold and a share of differing pixels), a diff image, a text
// summary and an HTML report with reference, new and diff side by side.
import { writeFileSync } from 'node:fs';
import { encode, decode } from 'fast-png';
import { RECORD_FIELDS } from '../web/app/deterministic/flight.js';

/**
 * The first difference between two lists of frame figures, as one line, or null.
 * @param {object[]} expected @param {object[]} actual
 * @param {string} what e.g. 'the reference', 'Node'
 */
export function compareStats(expected, actual, what) {
  if (expected.length !== actual.length) return `${actual.length} frames, ${what} has ${expected.length}`;
  for (let f = 0; f < expected.length; f++) {
    const e = expected[f], a = actual[f];
    for (const key of ['hash', ...RECORD_FIELDS]) {
      if (e[key] !== a[key]) return `frame ${f}: ${key} ${a[key]}, ${what} has ${e[key]}`;
    }
  }
  return null;
}

/** Reads an 8-bit RGB(A) PNG as {width, height, rgb}. */
export function readPng(bytes) {
  const image = decode(bytes);
  if (image.depth !== 8 || image.channels < 3) throw new Error(`expected an 8-bit RGB PNG, got ${image.depth}-bit with ${image.channels} channels`);
  const rgb = new Uint8Array(image.width * image.height * 3);
  for (let k = 0, j = 0; j < rgb.length; k += image.channels, j += 3) {
    rgb[j] = image.data[k];
    rgb[j + 1] = image.data[k + 1];
    rgb[j + 2] = image.data[k + 2];
  }
  return { width: image.width, height: image.height, rgb };
}

export function writePng(path, { width, height, rgb }) {
  writeFileSync(path, encode({ width, height, data: rgb, channels: 3, depth: 8 }));
}

/**
 * Compares two images pixel by pixel: a pixel differs when one of its channels differs by more
 * than `threshold` (0-255). Returns the count and share of differing pixels, the largest channel
 * difference, and a diff image: differing pixels red, smaller differences orange, the rest the
 * reference's grey, dimmed.
 */
export function compareImages(reference, actual, threshold) {
  if (reference.width !== actual.width || reference.height !== actual.height) {
    return { sizeMismatch: `${actual.width}x${actual.height}, the reference is ${reference.width}x${reference.height}` };
  }
  const { width, height } = reference;
  const a = reference.rgb, b = actual.rgb;
  const diff = new Uint8Array(width * height * 3);
  let differing = 0, maxDelta = 0;
  for (let p = 0; p < width * height; p++) {
    const k = 3 * p;
    const delta = Math.max(Math.abs(a[k] - b[k]), Math.abs(a[k + 1] - b[k + 1]), Math.abs(a[k + 2] - b[k + 2]));
    if (delta > maxDelta) maxDelta = delta;
    if (delta > threshold) {
      differing += 1;
      diff[k] = 255; diff[k + 1] = 0; diff[k + 2] = 0;
    } else if (delta > 0) {
      diff[k] = 255; diff[k + 1] = 170; diff[k + 2] = 0;
    } else {
      const grey = Math.round(0.25 * (0.2126 * a[k] + 0.7152 * a[k + 1] + 0.0722 * a[k + 2]));
      diff[k] = diff[k + 1] = diff[k + 2] = grey;
    }
  }
  return { differing, share: differing / (width * height), maxDelta, diff: { width, height, rgb: diff } };
}

const escapeHtml = (text) => String(text).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));

/** The one-line verdict of a flight. */
export function flightLine(result) {
  if (result.updated) return `updated (${result.frames} frames, ${result.captures.length} captures)`;
  if (result.problems.length === 0) {
    const deltas = result.captures.filter((c) => c.maxDelta !== undefined).map((c) => c.maxDelta);
    const pixels = deltas.length ? `, largest pixel difference ${Math.max(...deltas)}` : '';
    return `ok (${result.frames} frames, ${result.captures.length} captures${pixels})`;
  }
  return `REGRESSION: ${result.problems.join('; ')}`;
}

/** The HTML report: per flight its verdict and, per capture, reference, new and diff. */
export function htmlReport(results, { threshold, maxShare }) {
  const rows = results.map((r) => {
    const images = r.captures.map((c) => `
      <figure><figcaption>frame ${c.frame}${c.share !== undefined ? `: ${(100 * c.share).toFixed(3)} % of pixels differ by more than ${threshold}, max ${c.maxDelta}` : ''}${c.problem ? ` · <b>${escapeHtml(c.problem)}</b>` : ''}</figcaption>
        <div class="row">
          ${c.reference ? `<a href="${c.reference}"><img src="${c.reference}" alt="reference"></a>` : '<span class="none">no reference</span>'}
          <a href="${c.image}"><img src="${c.image}" alt="new"></a>
          ${c.diff ? `<a href="${c.diff}"><img src="${c.diff}" alt="diff"></a>` : ''}
        </div></figure>`).join('');
    return `<section class="${r.problems.length ? 'bad' : 'good'}"><h2>${escapeHtml(r.name)}</h2>
      <p>${escapeHtml(r.dem)} · ${escapeHtml(flightLine(r))}</p>
      <p class="legend">reference · new · diff (red: differs by more than ${threshold}; orange: by less)</p>${images}</section>`;
  }).join('\n');
  const failed = results.filter((r) => r.problems.length).length;
  return `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>hexlod regress: ${failed} of ${results.length} regressed</title>
<style>body{font:14px system-ui,sans-serif;margin:16px;background:#f4f5f7}section{background:#fff;margin:12px 0;padding:8px 12px;border-left:6px solid #3a3}
section.bad{border-color:#d33}.row{display:flex;gap:8px;flex-wrap:wrap}img{image-rendering:pixelated;border:1px solid #ccc;max-width:32vw}
figure{margin:8px 0}.legend{color:#666}.none{display:inline-block;width:200px;color:#a00}</style></head><body>
<h1>hexlod regress: ${failed ? `${failed} of ${results.length} flights regressed` : `all ${results.length} flights as the references`}</h1>
<p>Mesh hashes and per-frame figures compared exactly; pixels: a pixel differs when a channel differs by more than ${threshold},
a capture regresses when more than ${(100 * maxShare).toFixed(3)} % of its pixels differ.</p>
${rows}</body></html>\n`;
}
