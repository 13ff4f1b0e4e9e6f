// The page's settings table (web/app/settings_table.js) against the core: the core's defaults
// are read through the ABI (a settings struct of zeros means "default"; hexlod_diag_settings
// reports what each zero resolved to), so a change of a default on either side fails here
// unless the table says why the page differs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { createNodeCore } from '../../lib/node_core.js';
import { STREAM_LAYOUTS } from '../../web/core/core.js';
import { SETTINGS, defaultSettings, coreSettings, checkSetting, URL_KEYS } from '../../web/app/settings_table.js';

const core = await createNodeCore();
const EFFECTS = ['core', 'heights', 'camera', 'view', 'mesh', 'ground', 'tiles', 'earth', 'nodata', 'none'];
// Core fields the page decides outside the table: tau mode always, and the stream's normals
// follow what the renderer draws (frame_pipeline.js).
const OUTSIDE_TABLE = ['maxErrorM', 'noNormals'];

/** The core's defaults: a fresh terrain's settings, all zeros, as the core resolved them. */
function coreDefaults() {
  const terrain = core.createTerrain(4, 4, 'f32');
  terrain.configure({}); // writes the struct of zeros: every field "default"
  const defaults = terrain.settingsInForce();
  terrain.destroy();
  return defaults;
}
const asCore = (value) => (typeof value === 'string' ? STREAM_LAYOUTS[value] : Number(value));

test("each core setting's default in the table is the core's own, unless the table says why not", () => {
  const defaults = coreDefaults();
  let same = 0, differ = 0;
  for (const [key, s] of Object.entries(SETTINGS)) {
    if (!s.core) continue;
    const [field, toCore] = s.core;
    const page = asCore(toCore(s.default)), own = defaults[field];
    if (s.coreDiffers) {
      assert.notEqual(page, own, `${key}: the table says the page's default differs from the core's (${field} = ${own}); it no longer does`);
      differ++;
    } else {
      assert.equal(page, own, `${key}: the page's default (${field} = ${page}) is not the core's (${own})`);
      same++;
    }
  }
  assert.ok(same >= 5 && differ >= 3, `${same} equal, ${differ} differing on purpose`);
});

test('every field of hexlod_settings is driven by one table entry, or named as decided outside it', () => {
  const fields = Object.keys(coreSettings(defaultSettings()));
  const fromTable = Object.values(SETTINGS).filter((s) => s.core).map((s) => s.core[0]);
  assert.equal(new Set(fromTable).size, fromTable.length, 'no field is driven by two settings');
  const all = Object.keys(coreDefaults());
  assert.deepEqual([...fromTable, ...OUTSIDE_TABLE].sort(), all.sort());
  assert.deepEqual(fields.sort(), [...fromTable, 'maxErrorM'].sort());
});

test('every setting has a known effect, a valid default, and a URL key of its own', () => {
  for (const [key, s] of Object.entries(SETTINGS)) {
    assert.ok(EFFECTS.includes(s.effect), `${key}: effect ${s.effect}`);
    if (key !== 'cellSize') assert.equal(checkSetting(key, s.default), s.default, `${key}: its default passes its own check`);
    assert.ok(s.panel || s.url, `${key} is reachable from the panel or the URL`);
  }
  const names = URL_KEYS.map(([, name]) => name);
  assert.equal(new Set(names).size, names.length);
});

test('the check compares resolved defaults: a zero becomes the core default, and a moved table default disagrees', () => {
  // The same comparison, on a table whose tau default moved: it must disagree with the core.
  const defaults = coreDefaults();
  const [field, toCore] = SETTINGS.tau.core;
  assert.notEqual(toCore(SETTINGS.tau.default + 1), defaults[field]);
  // And the core resolves a zero to its default, not to zero.
  assert.equal(defaults.tauPx, 1);
  assert.equal(defaults.verticalScale, 1);
});

test('the debug flags are settings: timing on or off, forced tile sides 0 or from their least', () => {
  assert.equal(checkSetting('timing', '1'), true);
  assert.equal(checkSetting('normalTile', '0'), 0);
  assert.equal(checkSetting('normalTile', '16'), 16);
  assert.equal(checkSetting('imageTile', '64'), 64);
  assert.match(checkSetting('normalTile', '8').message, /^normaltile=8 is not 0 or a whole number of texels from 16 to 16384$/);
  assert.match(checkSetting('imageTile', '63').message, /^imagetile=63 is not 0 or a whole number/);
  assert.match(checkSetting('imageTile', '64.5').message, /^imagetile=64.5 is not/);
});

test('the address is read in web/app/ only: nothing that draws or loads reads URL flags of its own', () => {
  const root = new URL('../../web/', import.meta.url);
  const readers = readdirSync(root, { recursive: true }).filter((f) => f.endsWith('.js'))
    .filter((f) => /location\??\.search/.test(readFileSync(new URL(f, root), 'utf8')));
  assert.ok(readers.length > 0, 'the page reads its address somewhere');
  assert.deepEqual(readers.filter((f) => !f.startsWith('app/')), []);
});
