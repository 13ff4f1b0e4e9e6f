// No-data filling: every missing sample gets a height interpolated from the valid samples
// around it, so a void neither spikes to -32768 nor leaves a hole (the core would otherwise
// fill it with the lowest height, a pit with cliff walls).
//
// Each missing sample takes the mean of two linear interpolations across its gap: along its
// row and along its column, between the nearest valid samples on either side (or the one
// nearest valid sample where the gap reaches the edge). The mask of missing samples costs one
// bit a sample; the passes write in place, pausing between rows like the decoders.

import { HeightfieldError } from './common.js';

/**
 * @param {import('./pacing.js').SampleSink} sink holds the decoded samples (read and written in place)
 * @param {number} width
 * @param {number} height
 * @param {number|null} nodata raw value of a missing sample; NaN is always missing
 * @param {string} name file name, for the all-nodata message
 * @param {(k: number) => boolean} [isMissingAt] which samples are missing, by index, instead of by
 *   value: a mosaic's gaps between tiles hold no value that could say so (mosaic.js)
 * @returns {Promise<{count: number, mask: Uint8Array|null}>} how many samples were missing (and
 *   are now filled), and which: bit k & 7 of byte k >> 3 set for sample k (null when none was);
 *   the page can draw them as holes
 * @throws {HeightfieldError} when every sample is missing
 */
export async function fillNodata(sink, width, height, nodata, name, isMissingAt = null) {
  // Float samples hold float32 values: a no-data of -9999.9 (a double) is -9999.900390625 there.
  if (nodata !== null && sink.samples instanceof Float32Array) nodata = Math.fround(nodata);
  const isMissing = nodata === null || Number.isNaN(nodata)
    ? (v) => v !== v // NaN
    : (v) => v === nodata || v !== v;
  let samples = sink.samples;
  const integer = !(samples instanceof Float32Array);
  const store = integer ? Math.round : (v) => v;

  // Pass 1: mark the missing samples; fill each along its row.
  const mask = new Uint8Array(Math.ceil((width * height) / 8));
  let missing = 0;
  let rowsWithData = 0;
  for (let y = 0; y < height; y++) {
    const row = y * width;
    let lastValid = -1;
    for (let x = 0; x < width; x++) {
      const v = samples[row + x];
      if (isMissingAt ? !isMissingAt(row + x) : !isMissing(v)) {
        if (lastValid < x - 1) fillSpan(samples, row, lastValid, x, width, store);
        lastValid = x;
        continue;
      }
      const k = row + x;
      mask[k >> 3] |= 1 << (k & 7);
      missing++;
    }
    if (lastValid >= 0) {
      rowsWithData++;
      if (lastValid < width - 1) fillSpan(samples, row, lastValid, width, width, store);
    }
    await sink.pace((0.5 * y) / height);
    samples = sink.samples;
  }
  if (missing === 0) return { count: 0, mask: null };
  if (rowsWithData === 0) throw new HeightfieldError(name, `every sample is no-data (${describe(nodata)}): nothing to show`);

  // Pass 2: along columns, averaged with the row value (or alone where the row had no data).
  // Rows are swept top to bottom; a column's gap is filled when its lower end is found.
  const missingAt = (k) => (mask[k >> 3] >> (k & 7)) & 1;
  const lastValidRow = new Int32Array(width).fill(-1);
  const rowHadData = (y) => {
    for (let x = 0; x < width; x++) if (!missingAt(y * width + x)) return true;
    return false;
  };
  const emptyRows = new Uint8Array(height);
  for (let y = 0; y < height; y++) emptyRows[y] = rowHadData(y) ? 0 : 1;
  const blendColumn = (x, above, below) => {
    // Rows above+1 .. below-1 of column x are missing; above or below may be out of range.
    const a = above >= 0 ? samples[above * width + x] : samples[below * width + x];
    const b = below < height ? samples[below * width + x] : a;
    const span = below - above;
    for (let y = above + 1; y < below; y++) {
      const t = above >= 0 && below < height ? (y - above) / span : 0;
      const column = a + (b - a) * t;
      const k = y * width + x;
      samples[k] = emptyRows[y] ? store(column) : store((samples[k] + column) / 2);
    }
  };
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (missingAt(y * width + x)) continue;
      if (lastValidRow[x] < y - 1) blendColumn(x, lastValidRow[x], y);
      lastValidRow[x] = y;
    }
    await sink.pace(0.5 + (0.5 * y) / height);
    samples = sink.samples;
  }
  for (let x = 0; x < width; x++) {
    if (lastValidRow[x] < height - 1 && lastValidRow[x] >= 0) blendColumn(x, lastValidRow[x], height);
  }
  // A sample whose row and column both hold no data: copy the nearest row that had data (the
  // one above on a tie). Found for every row in two sweeps: searching outwards from each empty
  // row took 2.5 s for a 2 x 20000 field with one sample.
  const emptyColumns = [];
  for (let x = 0; x < width; x++) if (lastValidRow[x] < 0) emptyColumns.push(x);
  if (emptyColumns.length === 0) return { count: missing, mask };
  const nearest = new Int32Array(height).fill(-1); // the nearest row with data above, then either side
  for (let y = 0, above = -1; y < height; y++) nearest[y] = emptyRows[y] ? above : (above = y);
  for (let y = height - 1, below = -1; y >= 0; y--) {
    if (!emptyRows[y]) { below = y; continue; }
    if (below >= 0 && (nearest[y] < 0 || below - y < y - nearest[y])) nearest[y] = below;
    for (const x of emptyColumns) samples[y * width + x] = samples[nearest[y] * width + x];
  }
  return { count: missing, mask };
}

/** Linear fill of samples[row+from+1 .. row+to-1] between valid ends; from = -1 (no left
 *  end) or to = width (no right end) copies the other end. */
function fillSpan(samples, row, from, to, width, store) {
  const hasLeft = from >= 0, hasRight = to < width;
  const left = hasLeft ? samples[row + from] : samples[row + to];
  const right = hasRight ? samples[row + to] : left;
  for (let x = from + 1; x < to; x++) {
    const t = hasLeft && hasRight ? (x - from) / (to - from) : 0;
    samples[row + x] = store(left + (right - left) * t);
  }
}

function describe(nodata) {
  return nodata === null || Number.isNaN(nodata) ? 'NaN' : `value ${nodata}`;
}
