// The flights of the deterministic mode in Node: flight files are checked key by key, the camera
// path passes through its keyframes and has no jump in velocity, a replay gives the same mesh
// hashes every time and the ones stored by the page (tests/regress/flights/refs). `hexlod regress`
// (Node-only runs here; the browser's in tests/browser/regress.test.js): tolerances, masks and
// drift, what a mismatch names, missing references, bad flights in a folder, stale reports,
// JUnit and JSON, height fields by URL, references per platform and the exit codes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createNodeCore } from '../../lib/node_core.js';
import { readInputs } from '../../lib/cli_common.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { parseFlight, flightSettings, FlightCamera, FlightError, replayFlight, withKeyframes } from '../../web/app/deterministic/flight.js';
import { flightTrackKeyframes } from '../../web/app/deterministic/track_keyframes.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';
import { DEFAULT_TOLERANCE, toleranceFor } from '../../web/app/deterministic/tolerance.js';
import { compareImages, describeImage, flightChanges, flightRecordOf } from '../../lib/regress_compare.js';
import { readDem } from '../../lib/dem_source.js';
import { parse as junitParse } from 'junit2json';

const root = fileURLToPath(new URL('../../', import.meta.url));
const flights = join(root, 'tests/regress/flights');
const volcano = join(root, 'tests/fixtures/volcano_maungawhau.png');

function hexlod(args, env = {}) {
  return new Promise((resolve) => {
    execFile(process.execPath, [join(root, 'bin/hexlod.js'), ...args], { cwd: root, env: { ...process.env, ...env }, timeout: 120000 },
      (error, stdout, stderr) => resolve({ code: error ? error.code : 0, stdout, stderr }));
  });
}

const flightJson = (overrides = {}) => ({
  fps: 10,
  keyframes: [
    { time: 0, position: [100, 500, 100], target: [400, 100, 300] },
    { time: 1, position: [300, 400, 200], target: [500, 100, 400], fov: 40 },
    { time: 3, position: [600, 450, 300], target: [300, 100, 300] },
  ],
  ...overrides,
});

test('a flight file is checked key by key, and the message names the key', () => {
  const bad = [
    [[], /the file must hold a JSON object/],
    [flightJson({ keyframes: [] }), /"keyframes" must be a non-empty array/],
    [flightJson({ speed: 3 }), /"speed" is not a flight key/],
    [flightJson({ fps: 0 }), /"fps" must be a number from 1/],
    [flightJson({ settings: { tau: -1 } }), /"settings"."tau" must be a number/],
    [flightJson({ settings: { budget: 3 } }), /"settings"."budget" is not a setting/],
    [flightJson({ settings: { embedding: 'round' } }), /"settings"."embedding" must be one of exact, shifted/],
    [flightJson({ captures: [0, 99] }), /"captures"\[1\] must be an integer from 0 to 30/],
    [flightJson({ image: 3 }), /"image" must be a file path or an http\(s\) URL/],
    [flightJson({ worldFile: 'x.jgw' }), /"worldFile" goes with "image"/],
    [flightJson({ image: 'a.jpg', layers: [] }), /"image" goes into "layers" when a flight has them/],
    [flightJson({ layers: {} }), /"layers" must be an array/],
    [flightJson({ layers: [{ opacity: 1 }] }), /"layers"\[0\] needs "image" or "tiles"/],
    [flightJson({ layers: [{ image: 'a.jpg', tiles: 'x' }] }), /"layers"\[0\].tiles is not a key of an image layer/],
    [flightJson({ layers: [{ tiles: 'x', opacity: 3 }] }), /"layers"\[0\].opacity must be a number from 0 to 1/],
    [flightJson({ layers: [{ image: 'a.jpg', visible: 'no' }] }), /"layers"\[0\].visible must be true or false/],
    [flightJson({ settings: { imageOpacity: 2 } }), /"settings"."imageOpacity" must be a number from 0 to 1/],
    [flightJson({ settings: { imageUnlit: 1 } }), /"settings"."imageUnlit" must be true or false/],
  ];
  const keyframes = flightJson().keyframes;
  bad.push([flightJson({ keyframes: [keyframes[0], { ...keyframes[1], position: [1, 2] }] }), /"keyframes"\[1\].position must be three numbers/]);
  bad.push([flightJson({ keyframes: [keyframes[0], { ...keyframes[1], target: [1, 'x', 3] }] }), /"keyframes"\[1\].target\[1\] must be a number/]);
  bad.push([flightJson({ keyframes: [keyframes[1], keyframes[0]] }), /"keyframes"\[1\].time must be later/]);
  bad.push([flightJson({ keyframes: [{ time: 0, position: [1, 2, 3] }] }), /"keyframes"\[0\].target is missing/]);
  bad.push([flightJson({ keyframes: [{ time: 0, position: [1, 2, 3], target: [1, 2, 3] }] }), /"keyframes"\[0\].target must differ/]);
  bad.push([flightJson({ keyframes: [{ ...keyframes[0], zoom: 2 }] }), /"keyframes"\[0\].zoom is not a keyframe key/]);
  for (const [json, message] of bad) {
    assert.throws(() => parseFlight(json, 'f.json'), (e) => e instanceof FlightError && message.test(e.message) && e.message.startsWith('f.json: '),
      `expected ${message} for ${JSON.stringify(json).slice(0, 120)}`);
  }
  const flight = parseFlight(flightJson(), 'f.json');
  assert.equal(flight.frames, 31); // 3 s at 10 frames a second, both ends included
  assert.deepEqual(flight.captures, [0, 15, 30]);
  assert.equal(flight.keyframes[0].fov, 50);
  assert.deepEqual(flight.layers, []);
  assert.ok(!('imageOpacity' in flight.settings), 'a flight without image settings records none (its references stay as they were)');
  const draped = parseFlight(flightJson({ image: 'a.jpg', worldFile: 'a.jgw', settings: { imageOpacity: 0.5, imageUnlit: true } }), 'f.json');
  assert.deepEqual([draped.layers, draped.settings.imageOpacity, draped.settings.imageUnlit],
    [[{ kind: 'image', image: 'a.jpg', worldFile: 'a.jgw', opacity: 1, visible: true }], 0.5, true]);
  const settings = flightSettings(draped);
  assert.deepEqual([settings.imageOpacity, settings.imageUnlit], [0.5, true]);
  const record = (f) => flightRecordOf(f, { name: 'x.png', size: 1, sha256: 'ab' });
  assert.deepEqual(flightChanges(record(flight), record(draped)).filter((c) => /^(image|worldFile) /.test(c)), ['image none → a.jpg', 'worldFile none → a.jgw']);
  // Several layers, each with its look; a flight names them and a change names what changed.
  const layered = parseFlight(flightJson({ layers: [{ image: 'a.tif', opacity: 0.5 }, { tiles: 'http://t.example/{z}/{x}/{y}.png', visible: false }] }), 'f.json');
  assert.deepEqual(layered.layers, [{ kind: 'image', image: 'a.tif', worldFile: null, opacity: 0.5, visible: true },
    { kind: 'tiles', tiles: 'http://t.example/{z}/{x}/{y}.png', opacity: 1, visible: false }]);
  assert.deepEqual(flightChanges(record(draped), record(layered)).filter((c) => /^(image|worldFile|layers) /.test(c)),
    ['image a.jpg → none', 'worldFile a.jgw → none', 'layers none → a.tif (0.5), tiles http://t.example/{z}/{x}/{y}.png (hidden)']);
});

/** A terrain stand-in for the camera: 1000 x 600 m, heights 0..100, a flat ground at 50 m. */
const box = { width: 101, height: 61, spacingX: 10, spacingY: 10, minHeight: 0, maxHeight: 100, heightAt: () => 50 };

test('the camera path passes through its keyframes, with no jump in position or velocity between them', () => {
  const flight = parseFlight(flightJson({ fps: 1000, settings: { exaggeration: 2 } }), 'f.json');
  const camera = new FlightCamera(flight, box, 400, 200);
  for (const k of flight.keyframes) {
    const lod = camera.at(k.time * 1000);
    assert.deepEqual(lod.eye, [k.position[0], 2 * k.position[1], k.position[2]]);
    assert.deepEqual(lod.target, [k.target[0], 2 * k.target[1], k.target[2]]);
    assert.equal(camera.fovY, (k.fov * Math.PI) / 180);
  }
  // C1 at the keyframe at 1 s: the one-sided velocities differ by O(h) (a kink would leave a
  // difference that does not shrink with h): 4 frames apart the gap is about 4 times 1 frame's.
  const eyeAt = (f) => [...camera.at(f).eye];
  const gap = (h, axis) => {
    const [a, b, c] = [1000 - h, 1000, 1000 + h].map(eyeAt);
    return Math.abs((c[axis] - b[axis]) - (b[axis] - a[axis])) / h;
  };
  for (let axis = 0; axis < 3; axis++) {
    const ratio = gap(4, axis) / gap(1, axis);
    assert.ok(ratio > 3.5 && ratio < 4.5, `axis ${axis}: velocity gap ${gap(1, axis)} at 1 frame, ${gap(4, axis)} at 4 frames`);
  }
  // Between keyframes it moves: not a hold.
  assert.notDeepEqual(eyeAt(2000), eyeAt(2001));
  const lod = camera.at(500);
  assert.ok(lod.near > 0 && lod.far >= 10 * lod.near && lod.aspect === 2 && lod.viewportHeight === 200);
});

test('looking straight down, north is up (the view direction cannot be)', () => {
  const flight = parseFlight(flightJson({ keyframes: [
    { time: 0, position: [500, 900, 300], target: [500, 0, 300] },
    { time: 1, position: [200, 700, 100], target: [200, 0, 100] },
    { time: 2, position: [700, 400, 500], target: [700, 0, 500] },
  ] }), 'down.json');
  const camera = new FlightCamera(flight, box, 320, 180);
  for (let f = 0; f < flight.frames; f++) {
    const lod = camera.at(f);
    assert.equal(lod.eye[0], lod.target[0]);
    assert.equal(lod.eye[2], lod.target[2]);
    assert.deepEqual(lod.up, [0, 0, -1]);
  }
});

test('a replay in Node gives the same mesh hashes every time, and the ones the page stored', async () => {
  const core = await createNodeCore();
  const names = readdirSync(flights).filter((f) => f.endsWith('.flight.json') && !f.startsWith('himalaya'));
  assert.ok(names.length >= 6);
  const finalTriangles = new Map();
  for (const name of names) {
    const flight = parseFlight(JSON.parse(readFileSync(join(flights, name), 'utf8')), name);
    const runs = [];
    for (let run = 0; run < 2; run++) {
      useNodeCrsDefinitions();
      const { terrain, field } = await loadTerrain(core, readInputs(join(flights, flight.dem)), { encoding: 'auto', guessSpacing: true });
      // A flight along a track: its keyframes from the track on the terrain, as hexlod regress makes them.
      const track = flight.track && { name: flight.track.file.split('/').pop(), bytes: new Uint8Array(readFileSync(join(flights, flight.track.file))) };
      const flown = track ? withKeyframes(flight, await flightTrackKeyframes(flight.track, track, terrain, field.georef)) : flight;
      runs.push(replayFlight(terrain, flown, field.georef ?? null).toArray()); // on the Earth as the page draws it
      terrain.destroy();
    }
    assert.deepEqual(runs[0], runs[1], name);
    const stored = JSON.parse(readFileSync(join(flights, 'refs', name.replace('.flight.json', ''), 'stats.json'), 'utf8')).stats;
    assert.deepEqual(runs[0], stored, `${name}: Node and the stored page references differ`);
    assert.ok(new Set(stored.map((s) => s.hash)).size > stored.length / 2, `${name}: the mesh should change along the flight`);
    finalTriangles.set(name.replace('.flight.json', ''), stored.at(-1).triangles);
  }
  // The same path at a larger tolerance ends with fewer triangles.
  for (const [name, triangles] of finalTriangles) {
    if (name.endsWith('_tau1')) {
      const coarser = finalTriangles.get(name.replace('_tau1', '_tau4'));
      assert.ok(coarser < triangles, `${name}: ${triangles} triangles at tau 1, ${coarser} at tau 4`);
    }
  }
});

test('a flight\'s tolerance is checked key by key; captures override it, masks add up, the command line wins', () => {
  const bad = [
    [{ threshold: 2 }, /"tolerance"."threshold" must be a number from 0 to 1/],
    [{ maxDiffPixels: 1.5 }, /"tolerance"."maxDiffPixels" must be an integer/],
    [{ fuzz: 1 }, /"tolerance"."fuzz" is not a tolerance key/],
    [{ masks: [[0, 0, 10]] }, /"tolerance"."masks"\[0\] must be \[x, y, width, height\]/],
    [{ antialiasing: 'maybe' }, /"tolerance"."antialiasing" must be "ignore" or "count"/],
    [{ captures: { 7: {} } }, /"tolerance"."captures"."7" must name a captured frame \(0, 15, 30\)/],
    [{ captures: { 15: { captures: {} } } }, /"tolerance"."captures"."15"."captures" is not a tolerance key/],
  ];
  for (const [tolerance, message] of bad) {
    assert.throws(() => parseFlight(flightJson({ tolerance }), 'f.json'), (e) => e instanceof FlightError && message.test(e.message), message.source);
  }
  const flight = parseFlight(flightJson({ tolerance: { threshold: 0.1, masks: [[0, 0, 10, 10]],
    captures: { 15: { maxDiffPixels: 40, masks: [[20, 20, 5, 5]] } } } }), 'f.json');
  assert.deepEqual(toleranceFor(flight.tolerance, 0), { ...DEFAULT_TOLERANCE, threshold: 0.1, masks: [[0, 0, 10, 10]] });
  assert.deepEqual(toleranceFor(flight.tolerance, 15), { ...DEFAULT_TOLERANCE, threshold: 0.1, maxDiffPixels: 40, masks: [[0, 0, 10, 10], [20, 20, 5, 5]] });
  const cli = toleranceFor(flight.tolerance, 15, { threshold: 0.2, maxDiffPixelRatio: 0.5, masks: [[1, 2, 3, 4]] });
  assert.deepEqual([cli.threshold, cli.maxDiffPixels, cli.maxDiffPixelRatio, cli.masks.length], [0.2, 40, 0.5, 3]);
  const strict = toleranceFor(flight.tolerance, 15, { strict: true });
  assert.deepEqual([strict.threshold, strict.maxDiffPixels, strict.maxDiffPixelRatio, strict.antialiasing, strict.masks.length], [0, 0, 0, 'count', 2]);
});

/** A 200 x 100 test picture with gradients and edges, as a terrain view has. */
function picture() {
  const width = 200, height = 100, rgb = new Uint8Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const k = 3 * (y * width + x), ridge = x + 2 * y > 220;
      rgb.set([40 + (x >> 1), 90 + (y >> 1), ridge ? 200 : 60], k);
    }
  }
  return { width, height, rgb };
}
const changed = (image, change, where = () => true) => {
  const out = { ...image, rgb: image.rgb.slice() };
  for (let p = 0; p < image.width * image.height; p++) {
    if (where(p % image.width, Math.floor(p / image.width))) change(out.rgb, 3 * p);
  }
  return out;
};

test('pixels: a shift of two levels in half the picture fails by default; one level passes but is reported, and --strict fails it', () => {
  const reference = picture();
  const half = (x) => x < 100;
  const redTwo = compareImages(reference, changed(reference, (c, k) => { c[k] += 2; }, half), toleranceFor({ flight: {}, captures: {} }, 0));
  assert.equal(redTwo.passed, false);
  assert.equal(redTwo.changed, 10000);
  assert.ok(redTwo.differing > 9000, `${redTwo.differing} pixels differ`);
  assert.match(describeImage(redTwo, DEFAULT_TOLERANCE), /^\d+ pixels \(\d+\.\d+ %\) differ beyond threshold 0\.004, 40 \(0\.200 %\) allowed; 50\.00 % changed at all, mean change 1\.000, largest 2 of 255$/);

  const oneLevel = changed(reference, (c, k) => { c[k] += 1; c[k + 1] -= 1; c[k + 2] += 1; }, half);
  const drift = compareImages(reference, oneLevel, toleranceFor({ flight: {}, captures: {} }, 0));
  assert.equal(drift.passed, true);
  assert.equal(drift.differing, 0);
  assert.equal(drift.changedShare, 0.5);
  assert.equal(drift.meanChange, 0.5);
  assert.match(describeImage(drift, DEFAULT_TOLERANCE), /^50\.00 % changed at all, mean change 0\.500, largest 1 of 255$/);
  assert.equal(compareImages(reference, oneLevel, toleranceFor({ flight: {}, captures: {} }, 0, { strict: true })).passed, false);
  const same = compareImages(reference, reference, toleranceFor({ flight: {}, captures: {} }, 0, { strict: true }));
  assert.deepEqual([same.passed, same.changed, describeImage(same, DEFAULT_TOLERANCE)], [true, 0, 'identical']);
});

test('pixels: masks leave a region out, in CSS pixels scaled by the dpr; maxDiffPixels allows that many', () => {
  const reference = picture();
  const block = (x, y) => x >= 20 && x < 60 && y >= 10 && y < 30; // 40 x 20 device pixels
  const painted = changed(reference, (c, k) => c.set([255, 0, 255], k), block);
  const parsed = { flight: {}, captures: {} };
  const plain = compareImages(reference, painted, toleranceFor(parsed, 0));
  assert.deepEqual([plain.passed, plain.differing], [false, 800]);
  // The diff image marks exactly the block red.
  let red = 0;
  for (let k = 0; k < plain.diff.rgb.length; k += 3) if (plain.diff.rgb[k] === 255 && plain.diff.rgb[k + 1] === 0 && plain.diff.rgb[k + 2] === 0) red += 1;
  assert.equal(red, 800);
  // At dpr 2 the block is 20 x 10 CSS pixels from (10, 5).
  const masked = compareImages(reference, painted, toleranceFor(parsed, 0, { masks: [[10, 5, 20, 10]] }), 2);
  assert.deepEqual([masked.passed, masked.differing, masked.masked, masked.changed], [true, 0, 800, 0]);
  const halfMasked = compareImages(reference, painted, toleranceFor(parsed, 0, { masks: [[10, 5, 10, 10]] }), 2);
  assert.deepEqual([halfMasked.passed, halfMasked.differing], [false, 400]);
  assert.equal(compareImages(reference, painted, toleranceFor(parsed, 0, { maxDiffPixels: 800 })).passed, true);
  assert.equal(compareImages(reference, painted, toleranceFor(parsed, 0, { maxDiffPixels: 799 })).passed, false);
  assert.match(compareImages(reference, { width: 100, height: 200, rgb: reference.rgb }, DEFAULT_TOLERANCE).sizeMismatch,
    /100x200, the reference is 200x100/);
});

test('a mismatch names what changed in the flight: settings, viewport, keyframes, the height field', () => {
  const flight = parseFlight(flightJson({ settings: { tau: 1 } }), 'f.json');
  const dem = { name: 'a.png', size: 10, sha256: 'a'.repeat(64) };
  const before = flightRecordOf(flight, dem);
  assert.deepEqual(flightChanges(before, flightRecordOf(flight, dem)), []);
  const keyframes = flightJson().keyframes;
  const after = parseFlight(flightJson({ settings: { tau: 2, geomorph: false }, viewport: [640, 360],
    keyframes: [keyframes[0], { ...keyframes[1], fov: 45 }, keyframes[2]] }), 'f.json');
  assert.deepEqual(flightChanges(before, flightRecordOf(after, { ...dem, sha256: 'b'.repeat(64) })), [
    'tau 1 → 2', 'geomorph true → false', 'viewport 400x225 → 640x360', 'keyframe 1 fov 40 → 45',
    'height field a.png: its content changed (sha256 aaaaaaaa → bbbbbbbb)']);
  assert.deepEqual(flightChanges(before, flightRecordOf(flight, { ...dem, name: 'b.png' })), ['height field a.png → b.png']);
});

/** A scratch folder with a copy of one of our flights (its "dem" made absolute) and its reference. */
function scratch(name = 'volcano_down_tau1', edit = (f) => f) {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-regress-'));
  const flight = JSON.parse(readFileSync(join(flights, `${name}.flight.json`), 'utf8'));
  flight.dem = join(flights, flight.dem);
  writeFileSync(join(dir, `${name}.flight.json`), JSON.stringify(edit(flight)));
  cpSync(join(flights, 'refs', name), join(dir, 'refs', name), { recursive: true });
  return dir;
}

test('hexlod regress --node-only passes on the stored references; a changed hash names every differing frame; exit 1', async () => {
  const out = mkdtempSync(join(tmpdir(), 'hexlod-regress-'));
  const ok = await hexlod(['regress', flights, '--node-only', '--out', out]);
  assert.equal(ok.code, 0, ok.stdout + ok.stderr);
  assert.match(ok.stdout, /^hexlod regress: 8 flights: 8 passed \(Node only: figures, no pixels\)$/m);
  assert.match(ok.stdout, /^\[2\/8\] grandcanyon_tau1: ok: 21 frames, figures only \(\d+\.\d s\)$/m);
  rmSync(out, { recursive: true, force: true });

  const dir = scratch();
  try {
    const path = join(dir, 'refs/volcano_down_tau1/stats.json');
    const doc = JSON.parse(readFileSync(path, 'utf8'));
    doc.stats[5].hash = '0123456789abcdef';
    doc.stats[9].triangles += 6;
    writeFileSync(path, JSON.stringify(doc));
    const bad = await hexlod(['regress', join(dir, 'volcano_down_tau1.flight.json'), '--node-only', '--out', join(dir, 'out')]);
    assert.equal(bad.code, 1, bad.stdout + bad.stderr);
    const t9 = doc.stats[9].triangles;
    assert.match(bad.stdout, new RegExp(`volcano_down_tau1: REGRESSION: mesh: 2 of 21 frames differ from the reference \\(frame 5: hash … frame 9: triangles ${t9} → ${t9 - 6}\\)`));
    assert.match(bad.stdout, /^ {4}the flight and its height field are as the reference recorded them: the difference comes from hexlod/m);
    assert.match(bad.stdout, /^ {4}frame 5: the mesh \(hash\), same counts$/m);
    assert.match(bad.stdout, new RegExp(`^ {4}frame 9: triangles ${t9} → ${t9 - 6}$`, 'm'));
    const summary = readFileSync(join(dir, 'out/summary.txt'), 'utf8');
    assert.match(summary, /^hexlod regress: 1 flight: 1 regressed \(Node only/);
    assert.match(summary, /^exit code {2}1$/m);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('hexlod regress says what changed in the flight (tau 1 → 2), and lists the triangles of each frame before → after', async () => {
  const dir = scratch('volcano_down_tau1', (f) => ({ ...f, settings: { ...f.settings, tau: 2 } }));
  try {
    const { code, stdout } = await hexlod(['regress', join(dir, 'volcano_down_tau1.flight.json'), '--node-only', '--out', join(dir, 'out')]);
    assert.equal(code, 1, stdout);
    assert.match(stdout, /REGRESSION: the flight changed: tau 1 → 2; mesh: 21 of 21 frames differ from the reference \(frame 0: triangles \d+ → \d+ … frame 20: triangles \d+ → \d+\)/);
    assert.equal((stdout.match(/^ {4}frame \d+: triangles \d+ → \d+/gm) ?? []).length, 21);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('a missing reference is its own verdict, found before anything flies, with the command that makes one (exit 2)', async () => {
  const dir = scratch();
  try {
    rmSync(join(dir, 'refs'), { recursive: true });
    const flight = join(dir, 'volcano_down_tau1.flight.json');
    // No browser is started: a Chromium that cannot run would make it exit 3.
    const { code, stdout } = await hexlod(['regress', flight, '--chromium', '/bin/false', '--out', join(dir, 'out')]);
    assert.equal(code, 2, stdout);
    assert.match(stdout, /volcano_down_tau1: NO REFERENCE: no reference in .*refs\/volcano_down_tau1; make one with: hexlod regress \S+volcano_down_tau1\.flight\.json --update/);
    assert.match(stdout, /1 flight: 1 had no reference/);
    // The command it gives makes the reference, and the next run passes.
    const update = await hexlod(['regress', flight, '--node-only', '--update', '--out', join(dir, 'out')]);
    assert.equal(update.code, 0, update.stdout);
    assert.match(update.stdout, /volcano_down_tau1: reference written: 21 frames, figures only/);
    const again = await hexlod(['regress', flight, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(again.code, 0, again.stdout);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('in a folder, a flight file with a mistake fails alone and the others run; --grep picks flights by name', async () => {
  const dir = scratch();
  try {
    writeFileSync(join(dir, 'typo.flight.json'), JSON.stringify(flightJson({ setings: { tau: 2 } })));
    writeFileSync(join(dir, 'broken.flight.json'), '{ "keyframes": [ ');
    const { code, stdout } = await hexlod(['regress', dir, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(code, 2, stdout);
    assert.match(stdout, /\] broken: BAD INPUT: \S+broken\.flight\.json: not valid JSON/);
    assert.match(stdout, /\] typo: BAD INPUT: \S+typo\.flight\.json: "setings" is not a flight key/);
    assert.match(stdout, /\] volcano_down_tau1: ok: 21 frames, figures only/);
    assert.match(stdout, /3 flights: 2 had bad input, 1 passed/);

    const picked = await hexlod(['regress', dir, '--node-only', '--grep', '^volcano', '--out', join(dir, 'out')]);
    assert.equal(picked.code, 0, picked.stdout);
    assert.match(picked.stdout, /^hexlod regress: 1 flight: 1 passed/m);
    const none = await hexlod(['regress', dir, '--node-only', '--grep', 'canyon', '--out', join(dir, 'out')]);
    assert.equal(none.code, 2);
    assert.match(none.stderr, /no flight in .* matches --grep canyon \(broken, typo, volcano_down_tau1\)/);
    const badRegex = await hexlod(['regress', dir, '--grep', '(', '--out', join(dir, 'out')]);
    assert.equal(badRegex.code, 2);
    assert.match(badRegex.stderr, /--grep must be a regular expression/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('summary.txt, report.html, --junit and --json are rewritten by every run, also one that stops early', async () => {
  const dir = scratch();
  try {
    const flight = join(dir, 'volcano_down_tau1.flight.json');
    const out = join(dir, 'out');
    const files = ['--junit', join(dir, 'junit.xml'), '--json', join(dir, 'result.json')];
    const first = await hexlod(['regress', flight, '--node-only', '--out', out, ...files]);
    assert.equal(first.code, 0, first.stdout);
    assert.match(readFileSync(join(out, 'summary.txt'), 'utf8'), /1 passed/);
    assert.equal(JSON.parse(readFileSync(join(dir, 'result.json'), 'utf8')).exitCode, 0);
    // A second run whose height field does not load.
    writeFileSync(join(dir, 'broken.png'), readFileSync(volcano).subarray(0, 60));
    const second = await hexlod(['regress', join(dir, 'broken.png'), flight, '--node-only', '--out', out, ...files]);
    assert.equal(second.code, 2, second.stdout);
    const summary = readFileSync(join(out, 'summary.txt'), 'utf8');
    assert.match(summary, /volcano_down_tau1: BAD INPUT: \S+broken\.png: the height field does not load/);
    assert.doesNotMatch(summary, /passed/);
    assert.match(readFileSync(join(out, 'report.html'), 'utf8'), /broken\.png: the height field does not load/);
    const json = JSON.parse(readFileSync(join(dir, 'result.json'), 'utf8'));
    assert.deepEqual([json.exitCode, json.flights[0].verdict], [2, 'bad-input']);
    assert.match(readFileSync(join(dir, 'junit.xml'), 'utf8'), /<error type="bad-input"/);
    // A usage mistake, before any flight is known, rewrites them too.
    const third = await hexlod(['regress', flight, '--threshold', '8', '--out', out]);
    assert.equal(third.code, 2);
    assert.match(third.stderr, /^hexlod: --threshold must be at most 1, got '8'; see hexlod regress --help\n$/);
    assert.match(readFileSync(join(out, 'summary.txt'), 'utf8'), /^hexlod regress: stopped: --threshold must be at most 1/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('JUnit XML that a JUnit parser reads: a test case per flight, failures for regressions, errors for bad input', async () => {
  const dir = scratch();
  try {
    writeFileSync(join(dir, 'typo.flight.json'), JSON.stringify(flightJson({ speed: 3 })));
    const path = join(dir, 'refs/volcano_down_tau1/stats.json');
    const doc = JSON.parse(readFileSync(path, 'utf8'));
    doc.stats[3].triangles += 2;
    writeFileSync(path, JSON.stringify(doc));
    const { code } = await hexlod(['regress', dir, '--node-only', '--out', join(dir, 'out'), '--junit', join(dir, 'junit.xml')]);
    assert.equal(code, 2);
    const report = await junitParse(readFileSync(join(dir, 'junit.xml'), 'utf8'));
    assert.equal(report.tests, 2);
    assert.equal(report.failures, 1);
    assert.equal(report.errors, 1);
    const cases = report.testsuite[0].testcase;
    assert.deepEqual(cases.map((c) => c.name), ['typo', 'volcano_down_tau1']);
    assert.equal(cases[0].error[0].type, 'bad-input');
    assert.match(cases[0].error[0].message, /"speed" is not a flight key/);
    assert.equal(cases[1].failure[0].type, 'regression');
    assert.match(cases[1].failure[0].inner, /frame 3: triangles \d+ → \d+/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('a height field by http URL, in a flight or on the command line, with its sidecar; a failing URL is named whole (exit 2)', async () => {
  const server = createServer((req, res) => {
    const path = join(root, 'tests/fixtures', decodeURIComponent(req.url.split('?')[0]).replace(/^\/dem\//, ''));
    if (!req.url.startsWith('/dem/') || !existsSync(path)) {
      res.writeHead(404).end('not found');
      return;
    }
    res.writeHead(200, { 'Content-Type': 'application/octet-stream' }).end(readFileSync(path));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const base = `http://127.0.0.1:${server.address().port}/dem/`;
  const dir = scratch('volcano_down_tau1', (f) => ({ ...f, dem: `${base}volcano_maungawhau.png` }));
  try {
    const flight = join(dir, 'volcano_down_tau1.flight.json');
    const ok = await hexlod(['regress', flight, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(ok.code, 0, ok.stdout + ok.stderr);
    // The same bytes as the file: the reference's height field has not changed.
    assert.match(ok.stdout, /volcano_down_tau1: ok: 21 frames/);
    const given = await hexlod(['regress', `${base}volcano_maungawhau.png`, flight, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(given.code, 0, given.stdout + given.stderr);
    const missing = await hexlod(['regress', `${base}nothing.png`, flight, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(missing.code, 2);
    assert.match(missing.stdout, new RegExp(`BAD INPUT: ${base.replace(/[.]/g, '\\.')}nothing\\.png: the server answered HTTP 404`));
    const ftp = await hexlod(['regress', 'ftp://example.org/x.png', flight, '--node-only', '--out', join(dir, 'out')]);
    assert.equal(ftp.code, 2);
    assert.match(ftp.stdout + ftp.stderr, /ftp:\/\/example\.org\/x\.png: only http and https URLs can be read/);
  } finally {
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});

test('a sidecar comes with a height field by URL', async () => {
  const server = createServer((req, res) => {
    const name = req.url.replace(/^\//, '');
    const path = join(root, 'tests/fixtures', name);
    if (!existsSync(path)) return void res.writeHead(404).end();
    res.writeHead(200).end(readFileSync(path));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  try {
    const dem = await readDem(`http://127.0.0.1:${server.address().port}/volcano_maungawhau.f32`);
    assert.deepEqual(dem.files.map((f) => f.name), ['volcano_maungawhau.f32', 'volcano_maungawhau.json']);
    assert.equal(dem.size, readFileSync(join(root, 'tests/fixtures/volcano_maungawhau.f32')).length);
    const local = await readDem(join(root, 'tests/fixtures/volcano_maungawhau.f32'));
    assert.equal(dem.sha256, local.sha256);
  } finally {
    server.close();
  }
});

test('references per platform: --platform keeps them in refs/NAME/PLATFORM/', async () => {
  const dir = scratch();
  try {
    const flight = join(dir, 'volcano_down_tau1.flight.json');
    const missing = await hexlod(['regress', flight, '--node-only', '--platform', 'linux-test', '--out', join(dir, 'out')]);
    assert.equal(missing.code, 2);
    assert.match(missing.stdout, /no reference in \S+refs\/volcano_down_tau1\/linux-test; make one with: .* --platform linux-test --update/);
    const update = await hexlod(['regress', flight, '--node-only', '--update', '--platform', 'linux-test', '--out', join(dir, 'out')]);
    assert.equal(update.code, 0, update.stdout);
    assert.ok(existsSync(join(dir, 'refs/volcano_down_tau1/linux-test/stats.json')));
    const ok = await hexlod(['regress', flight, '--node-only', '--platform', 'linux-test', '--out', join(dir, 'out')]);
    assert.equal(ok.code, 0, ok.stdout);
    const bad = await hexlod(['regress', flight, '--platform', '../up', '--out', join(dir, 'out')]);
    assert.equal(bad.code, 2);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('exit codes: 2 for usage and bad input, 3 when the browser cannot run, each with one line on stderr', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-bad-'));
  try {
    const flightPath = join(dir, 'f.flight.json');
    writeFileSync(flightPath, JSON.stringify(flightJson()));
    const cases = [
      [['regress', join(dir, 'missing.png'), flightPath], 2, /missing\.png: no such file/],
      [['regress', volcano, flightPath, '--strict', '--threshold', '0.1'], 2, /--strict takes no --threshold/],
      [['regress', volcano, flightPath, '--jobs', '0'], 2, /--jobs must be at least 1/],
      [['regress', volcano, flightPath, '--mask', '1,2,3'], 2, /--mask must be X,Y,W,H/],
      [['regress', join(dir, 'nothing')], 2, /nothing: no such file or folder/],
      [['regress', volcano, flightPath, '--update', '--chromium', join(dir, 'no-chromium')], 3, /^hexlod: no Chromium at .*no-chromium \(--chromium\): name the Chromium program, or install one with apt-get install chromium \(Debian\) or npx playwright-core install chromium$/m],
      [['regress', volcano, flightPath, '--update', '--chromium', '/bin/false'], 3, /Chromium at \/bin\/false did not start: the program exited at once/],
    ];
    for (const [args, exit, message] of cases) {
      const { code, stderr } = await hexlod([...args, '--out', join(dir, 'out')]);
      assert.equal(code, exit, `${args.join(' ')}: ${stderr}`);
      assert.match(stderr, message);
      assert.equal(stderr.trim().split('\n').length, 1, stderr);
      assert.doesNotMatch(stderr, /Target page, context or browser/);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
