// The overview of a streamed image (web/imagery/overview_rows.js): the box-filter mean of the
// pixels under each texel, every row once and in order, whatever the bands' heights.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { OverviewRows } from '../../web/imagery/overview_rows.js';

function image(width, height) {
  const rgba = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
    const i = (y * width + x) * 4;
    rgba.set([(x * 7 + y) & 255, (y * 3) & 255, (x ^ y) & 255, 255], i);
  }
  return rgba;
}

/** The same overview computed directly from the whole image. */
function expected(rgba, width, height, ow, oh) {
  const sums = new Float64Array(ow * oh * 5);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
    const o = (Math.min(oh - 1, Math.floor((y * oh) / height)) * ow + Math.min(ow - 1, Math.floor((x * ow) / width))) * 5;
    for (let c = 0; c < 4; c++) sums[o + c] += rgba[(y * width + x) * 4 + c];
    sums[o + 4]++;
  }
  return Uint8Array.from({ length: ow * oh * 4 }, (_, i) => Math.round(sums[Math.floor(i / 4) * 5 + (i % 4)] / sums[Math.floor(i / 4) * 5 + 4]));
}

test('the overview of streamed bands is the box-filter mean of the whole image', () => {
  for (const [w, h, ow, oh, band] of [[100, 70, 25, 18, 7], [257, 129, 64, 32, 1], [40, 40, 40, 40, 40], [1000, 3, 7, 1, 2]]) {
    const rgba = image(w, h), got = new Uint8Array(ow * oh * 4), rows = [];
    const overview = new OverviewRows(w, h, ow, oh, (row, out) => { rows.push(row); got.set(out, row * ow * 4); });
    for (let y = 0; y < h; y += band) overview.add(y, Math.min(band, h - y), rgba.subarray(y * w * 4, Math.min(h, y + band) * w * 4));
    overview.finish();
    assert.deepEqual(rows, Array.from({ length: oh }, (_, i) => i), `${w}x${h} -> ${ow}x${oh}: every row once, in order`);
    assert.deepEqual(got, expected(rgba, w, h, ow, oh), `${w}x${h} -> ${ow}x${oh} in bands of ${band}`);
  }
  const o = new OverviewRows(10, 10, 5, 5, () => {});
  assert.throws(() => o.add(3, 1, new Uint8Array(40)), /rows must come in order/);
});
