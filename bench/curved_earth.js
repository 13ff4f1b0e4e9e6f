#!/usr/bin/env node
// What drawing on the curved Earth costs the core: the regression flight over the default
// terrain (tests/regress/flights/himalaya_tau2.flight.json: the Himalaya, 1,650 km of a
// geographic grid, τ 2, 1000 operations a frame) replayed in Node on the plane and on the
// Earth, alternating, N times each. Prints the median core time of the whole flight each way,
// their ratio (wall clock in one run), and the triangles drawn. Figures printed, never asserted.
//
//   node bench/curved_earth.js [--runs N]   (default 5)
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { countOption } from '../lib/script_options.js';
import { createNodeCore } from '../lib/node_core.js';
import { readNamedFile } from '../lib/image_files.js';
import { median, formatMs } from '../lib/page_frames.js';
import { loadTerrain } from '../web/loaders/terrain_source.js';
import { parseFlight, replayFlight } from '../web/app/deterministic/flight.js';

const USAGE = 'usage: node bench/curved_earth.js [--runs N]\n  N replays of the flight each way, alternating (default 5)';
const { count: runs, exitCode } = countOption('bench/curved_earth.js', USAGE, 'runs', 5);
if (runs === null) process.exit(exitCode);

const root = fileURLToPath(new URL('..', import.meta.url));
const flightFile = `${root}tests/regress/flights/himalaya_tau2.flight.json`;
const json = JSON.parse(readFileSync(flightFile, 'utf8'));
const dem = new URL(json.dem, `file://${flightFile}`).pathname;
const core = await createNodeCore();
const files = [await readNamedFile(dem, 'height field'), await readNamedFile(dem.replace(/\.png$/, '.json'), 'sidecar')];
const { terrain, field } = await loadTerrain(core, files, { encoding: 'auto' });

const times = { flat: [], curved: [] }, drawn = {};
let frames = 0;
// One untimed replay each way first: the engine compiles the core's hot paths on it.
for (let k = -1; k < runs; k++) {
  for (const earth of ['flat', 'curved']) {
    const flight = parseFlight({ ...json, settings: { ...json.settings, earth } }, 'himalaya_tau2');
    const start = performance.now();
    const record = replayFlight(terrain, flight, field.georef ?? null).toArray();
    if (k >= 0) times[earth].push(performance.now() - start);
    drawn[earth] = record.reduce((sum, f) => sum + f.triangles, 0) / record.length;
    frames = record.length;
  }
}
terrain.destroy();
const flat = median(times.flat), curved = median(times.curved);
console.log(`flight   ${frames} frames of himalaya_tau2, ${runs} runs each way, alternating`);
console.log(`flat     ${formatMs(flat)} the flight, ${Math.round(drawn.flat)} triangles a frame on average`);
console.log(`curved   ${formatMs(curved)} the flight, ${Math.round(drawn.curved)} triangles a frame on average`);
console.log(`ratio    ${(curved / flat).toFixed(2)} the time, ${(drawn.curved / drawn.flat).toFixed(2)} the triangles (curved / flat)`);
