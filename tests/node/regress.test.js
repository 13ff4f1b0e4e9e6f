// The flights of the deterministic mode in Node: flight files are checked key by key, the camera
// path passes through its keyframes and has no jump in velocity, a replay gives the same mesh
// hashes every time and the ones stored by the page (tests/regress/flights/refs), and
// `hexlod regress` says in one line what is wrong with a bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { cpSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createNodeCore } from '../../bin/node_core.js';
import { readInputs } from '../../bin/cli_common.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { parseFlight, FlightCamera, FlightError, replayFlight } from '../../web/app/deterministic/flight.js';

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
      const { terrain } = await loadTerrain(core, readInputs(join(flights, flight.dem)), { encoding: 'auto', guessSpacing: true });
      runs.push(replayFlight(terrain, flight).toArray());
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

test('hexlod regress --node-only passes on the stored references and fails on a changed hash', async () => {
  const ok = await hexlod(['regress', flights, '--node-only', '--out', mkdtempSync(join(tmpdir(), 'hexlod-regress-'))]);
  assert.equal(ok.code, 0, ok.stdout + ok.stderr);
  assert.match(ok.stdout, /7 flights, 0 regressed/);

  const refs = mkdtempSync(join(tmpdir(), 'hexlod-refs-'));
  try {
    cpSync(join(flights, 'refs/volcano_down_tau1'), join(refs, 'volcano_down_tau1'), { recursive: true });
    const path = join(refs, 'volcano_down_tau1/stats.json');
    const doc = JSON.parse(readFileSync(path, 'utf8'));
    doc.stats[5].hash = '0123456789abcdef';
    writeFileSync(path, JSON.stringify(doc));
    const bad = await hexlod(['regress', join(flights, 'volcano_down_tau1.flight.json'), '--node-only', '--refs', refs, '--out', join(refs, 'out')]);
    assert.equal(bad.code, 1);
    assert.match(bad.stdout, /volcano_down_tau1: REGRESSION: frame 5: hash [0-9a-f]{16}, the reference has 0123456789abcdef/);
  } finally {
    rmSync(refs, { recursive: true, force: true });
  }
});

test('hexlod regress says in one line what is wrong with its inputs', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-bad-'));
  try {
    const flightPath = join(dir, 'f.flight.json');
    writeFileSync(flightPath, JSON.stringify(flightJson()));
    writeFileSync(join(dir, 'syntax.json'), '{ "keyframes": [ ');
    writeFileSync(join(dir, 'key.json'), JSON.stringify(flightJson({ settings: { tau: 'fine' } })));
    writeFileSync(join(dir, 'broken.png'), readFileSync(volcano).subarray(0, 60));
    const cases = [
      [['regress', join(dir, 'missing.png'), flightPath], /missing\.png: no such file/],
      [['regress', volcano, join(dir, 'missing.json')], /missing\.json: no such file/],
      [['regress', volcano, join(dir, 'syntax.json')], /syntax\.json: not valid JSON/],
      [['regress', volcano, join(dir, 'key.json')], /key\.json: "settings"\."tau" must be a number/],
      [['regress', join(dir, 'broken.png'), flightPath], /broken\.png: the height field does not load/],
      [['regress', volcano, flightPath, '--chromium', join(dir, 'no-chromium')], /no Chromium at .*no-chromium/],
      [['regress', join(dir, 'f.flight.json')], /no "dem" key and no height field/],
    ];
    for (const [args, message] of cases) {
      const { code, stdout, stderr } = await hexlod([...args, '--out', join(dir, 'out')]);
      assert.equal(code, 1, `${args.join(' ')}: ${stderr}`);
      assert.equal(stdout, '');
      assert.match(stderr, message);
      assert.equal(stderr.trim().split('\n').length, 1, stderr);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
