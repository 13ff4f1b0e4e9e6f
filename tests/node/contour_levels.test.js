// Contour levels (web/measure/contour_levels.js): the interval as typed, 'auto', and the widening
// of an interval that would draw too many lines; the settings table and the URL read it; and a
// regression flight can turn contours on with an interval.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseContourInterval, contourLevels, countLevels, MAJOR_EVERY } from '../../web/measure/contour_levels.js';
import { checkSetting, SETTINGS } from '../../web/app/settings_table.js';
import { parseUrlState } from '../../web/app/url_state.js';
import { parseFlight, flightSettings, FlightError } from '../../web/app/deterministic/flight.js';
import { heightTexturePlan, MAX_TEXELS } from '../../web/render/contours/height_texture.js';

const isNice = (v) => {
  const m = v / 10 ** Math.floor(Math.log10(v) + 1e-9);
  return [1, 2, 5].some((n) => Math.abs(m - n) < 1e-9);
};

test('an interval is a positive number of metres or auto; anything else is refused with a message', () => {
  assert.equal(parseContourInterval('auto'), 'auto');
  assert.equal(parseContourInterval(' AUTO '), 'auto');
  assert.equal(parseContourInterval('50'), 50);
  assert.equal(parseContourInterval(' 2.5 '), 2.5);
  assert.equal(parseContourInterval('1e2'), 100);
  assert.equal(parseContourInterval(20), 20);
  for (const bad of ['0', '-5', 'abc', '', ' ', 'NaN', 'Infinity', '-Infinity', '1e400', '0x10', '5m', '1,5', 0, -1, NaN, Infinity]) {
    assert.throws(() => parseContourInterval(bad), (error) => error instanceof Error && /contour interval/.test(error.message)
      && /positive number of metres or auto/.test(error.message), `${JSON.stringify(String(bad))} is refused`);
  }
});

test("'auto' picks a 1-2-5 interval giving about 20 to 40 lines over the height range", () => {
  for (const [low, high] of [[479, 2347], [0, 8848], [94, 195], [-10, 10], [-10994, 8848], [1000.2, 1000.9], [0, 1e6]]) {
    const levels = contourLevels('auto', low, high);
    assert.ok(isNice(levels.interval), `${levels.interval} for ${low}..${high} is 1, 2 or 5 times a power of ten`);
    const lines = countLevels(levels.interval, low, high);
    assert.ok(lines >= 15 && lines <= 50, `${lines} lines for ${low}..${high} at ${levels.interval} m`);
    assert.equal(levels.widened, false);
    assert.equal(levels.message, '');
    assert.equal(levels.majorEvery, MAJOR_EVERY);
    assert.equal(levels.major, levels.interval * MAJOR_EVERY);
  }
  assert.equal(contourLevels('auto', 479, 2347).interval, 50);
  assert.equal(contourLevels('auto', 5, 5).interval > 0, true, 'a flat field still has an interval');
});

test('a given interval is kept while it draws at most maxLines; past that it is widened to a 1-2-5 value, with a message', () => {
  const kept = contourLevels(10, 479, 2347);
  assert.deepEqual([kept.interval, kept.widened, kept.message], [10, false, '']);
  assert.equal(contourLevels(3.7, 0, 100).interval, 3.7, 'an interval the user typed is not rounded');
  const tiny = contourLevels(0.01, 479, 2347);
  assert.equal(tiny.widened, true);
  assert.ok(isNice(tiny.interval) && tiny.interval > 0.01);
  assert.ok(countLevels(tiny.interval, 479, 2347) <= 500, `${countLevels(tiny.interval, 479, 2347)} lines`);
  assert.ok(countLevels(tiny.interval / 2, 479, 2347) > 500 || !isNice(tiny.interval / 2), 'the smallest nice interval that fits');
  assert.match(tiny.message, /0\.01 m would draw \d+ lines; widened to 5 m/);
  const capped = contourLevels(1, 0, 8848, 100);
  assert.equal(capped.widened, true);
  assert.ok(countLevels(capped.interval, 0, 8848) <= 100);
  assert.equal(capped.interval, 100);
  assert.throws(() => contourLevels(0, 0, 1), /positive/);
});

test('the settings table and the URL read contours and the interval; a refused value names why', () => {
  assert.equal(SETTINGS.contours.url, 'contours');
  assert.equal(SETTINGS.contourInterval.url, 'cint');
  assert.equal(checkSetting('contourInterval', 'auto'), 'auto');
  assert.equal(checkSetting('contourInterval', '25'), 25);
  for (const bad of ['0', '-5', 'abc']) assert.match(checkSetting('contourInterval', bad).message, /contour interval/);
  assert.equal(checkSetting('contours', true), true);
  const url = parseUrlState('?contours=1&cint=50');
  assert.deepEqual(url.settings, { contours: true, contourInterval: 50 });
  assert.deepEqual(url.errors, []);
  assert.deepEqual(parseUrlState('?contours=0&cint=auto').settings, { contours: false, contourInterval: 'auto' });
  const bad = parseUrlState('?contours=maybe&cint=-5');
  assert.deepEqual(bad.settings, {});
  assert.equal(bad.errors.length, 2);
  assert.match(bad.errors.join('; '), /contours is on or off.*contour interval -5/);
});

test('a regression flight turns contours on with an interval, and refuses a bad one naming the key', () => {
  const flight = (settings) => ({ dem: 'x.png', settings, keyframes: [{ time: 0, position: [0, 1000, 0], target: [100, 0, 100] }] });
  const on = parseFlight(flight({ contours: true, contourInterval: 25 }), 'on.json');
  assert.deepEqual([on.settings.contours, on.settings.contourInterval], [true, 25]);
  const settings = flightSettings(on);
  assert.deepEqual([settings.contours, settings.contourInterval], [true, 25]);
  assert.equal(parseFlight(flight({ contours: true, contourInterval: 'auto' })).settings.contourInterval, 'auto');
  // A flight without them keeps the page's defaults and records nothing new.
  const plain = parseFlight(flight({}));
  assert.equal('contours' in plain.settings, false);
  assert.equal(flightSettings(plain).contours, false);
  assert.throws(() => parseFlight(flight({ contourInterval: 0 }), 'zero.json'),
    (e) => e instanceof FlightError && /zero\.json: "settings"\."contourInterval" contour interval 0/.test(e.message));
  assert.throws(() => parseFlight(flight({ contours: 'yes' }), 'b.json'), (e) => e instanceof FlightError && /"contours" must be true or false/.test(e.message));
});

test("the exact height texture holds every sample up to 8193², then every k-th; its tiles share edges and cover the field", () => {
  const whole = heightTexturePlan(512, 512, 16384);
  assert.deepEqual(whole, { stride: 1, texelsX: 512, texelsZ: 512, tileX: 512, tileZ: 512, tilesX: 1, tilesZ: 1 });
  // The paper's 16385² field: over the cap, so every 2nd sample (8193² texels, one tile).
  const big = heightTexturePlan(16385, 16385, 16384);
  assert.equal(big.stride, 2);
  assert.deepEqual([big.texelsX, big.texelsZ], [8193, 8193]);
  assert.equal(heightTexturePlan(16386, 16385, 16384).stride, 3, 'one column more: every 3rd');
  assert.ok(big.texelsX * big.texelsZ <= MAX_TEXELS);
  // At full resolution with small tiles: tiles overlap by one texel and reach the last sample.
  for (const [w, h, tile] of [[8193, 4097, 4096], [100, 37, 16], [17, 17, 16]]) {
    const p = heightTexturePlan(w, h, tile);
    assert.equal(p.stride, 1);
    assert.ok(p.tileX <= tile && p.tileZ <= tile);
    assert.ok((p.tilesX - 1) * (p.tileX - 1) < p.texelsX - 1 && p.tilesX * (p.tileX - 1) >= p.texelsX - 1, `${w}: columns covered`);
    assert.ok((p.tilesZ - 1) * (p.tileZ - 1) < p.texelsZ - 1 && p.tilesZ * (p.tileZ - 1) >= p.texelsZ - 1, `${h}: rows covered`);
  }
});
