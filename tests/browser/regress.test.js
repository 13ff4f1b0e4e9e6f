// Our own regression flights (tests/regress/flights) through `hexlod regress`: every flight flown
// in headless Chromium gives the mesh hashes and figures of its Node replay and of the stored
// references, and identical pixels. A changed reference is caught: a painted block in an image
// shows up in the diff and the report's comparer, a changed triangle count in the figures, exit
// code 1. A real shader change (the lowland colour's red 0.14 → 0.15) is caught by the default
// tolerance. --jobs 2 gives what --jobs 1 gives, and a height field by URL flies as the file.
// References are rewritten with: node bin/hexlod.js regress tests/regress/flights --update
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { decode, encode } from 'fast-png';
import { readPng, writePng } from '../../lib/regress_compare.js';
import { startBrowser } from '../../lib/regress_browser.js';
import { startTileServer } from '../../lib/tile_server.js';
import { BLUE_MARBLE_POINTS, groundPoint, screenPoint, colourAt, coloursMatch } from '../../lib/draped_points.js';
import { parseFlight, FlightCamera } from '../../web/app/deterministic/flight.js';
import { ScriptedCamera } from '../../web/app/deterministic/mode.js';

const root = fileURLToPath(new URL('../../', import.meta.url));
const flights = join(root, 'tests/regress/flights');
const outDir = join(root, 'tests/out/regress');

function hexlod(args, project = root) {
  return new Promise((resolve) => {
    execFile(process.execPath, [join(project, 'bin/hexlod.js'), ...args], { cwd: root, timeout: 600000, maxBuffer: 16 << 20 },
      (error, stdout, stderr) => resolve({ code: error ? error.code : 0, stdout, stderr }));
  });
}

/** Files of two output folders that differ (names, or bytes), as a list. */
function differingFiles(a, b) {
  const list = (dir) => readdirSync(dir, { recursive: true }).filter((f) => /\.(png|json)$/.test(f)).sort();
  const names = list(a);
  const problems = names.join() === list(b).join() ? [] : [`file lists differ: ${names.join()} / ${list(b).join()}`];
  for (const name of names) {
    if (existsSync(join(b, name)) && !readFileSync(join(a, name)).equals(readFileSync(join(b, name)))) problems.push(name);
  }
  return problems;
}

test('every regression flight matches Node and its references, hashes exactly and pixels within the tolerance', async () => {
  const names = readdirSync(flights).filter((f) => f.endsWith('.flight.json')).map((f) => f.replace('.flight.json', ''));
  const { code, stdout, stderr } = await hexlod(['regress', flights, '--out', outDir]);
  assert.equal(code, 0, `${stdout}\n${stderr}`);
  // Byte-identical pixels on one machine: SwiftShader is deterministic.
  for (const name of names) assert.match(stdout, new RegExp(`\\] ${name}: ok: 21 frames, [12] captures?; pixels identical`), `${name}\n${stdout}`);
  assert.match(stdout, new RegExp(`hexlod regress: ${names.length} flights: ${names.length} passed`));
  const report = readFileSync(join(outDir, 'report.html'), 'utf8');
  assert.match(report, /<title>hexlod regress: 8 flights: 8 passed<\/title>/);
  assert.ok(existsSync(join(outDir, 'grandcanyon_tau1/frame-0020-diff.png')));
});

test('--jobs 2 flies two pages at once and writes what --jobs 1 wrote, byte for byte', async () => {
  const out = mkdtempSync(join(tmpdir(), 'hexlod-jobs-'));
  try {
    const { code, stdout } = await hexlod(['regress', flights, '--jobs', '2', '--out', out]);
    assert.equal(code, 0, stdout);
    assert.deepEqual(differingFiles(outDir, out), []);
    const summary = (dir) => readFileSync(join(dir, 'summary.txt'), 'utf8').replace(/^report .*$/m, '');
    assert.equal(summary(out), summary(outDir));
  } finally {
    rmSync(out, { recursive: true, force: true });
  }
});

test('a changed reference is caught: pixels in the diff image, figures by frame, exit code 1', async () => {
  const refs = mkdtempSync(join(tmpdir(), 'hexlod-refs-'));
  const out = join(refs, 'out');
  try {
    const name = 'volcano_down_tau4';
    cpSync(join(flights, 'refs', name), join(refs, name), { recursive: true });
    // A 40 x 20 magenta block in the reference of frame 20: 800 of 57,600 pixels (1.4 %).
    const path = join(refs, name, 'frame-0020.png');
    const image = readPng(readFileSync(path));
    for (let y = 50; y < 70; y++) {
      for (let x = 100; x < 140; x++) image.rgb.set([255, 0, 255], 3 * (y * image.width + x));
    }
    writePng(path, image);
    const statsPath = join(refs, name, 'stats.json');
    const doc = JSON.parse(readFileSync(statsPath, 'utf8'));
    doc.stats[12].triangles += 6;
    writeFileSync(statsPath, JSON.stringify(doc));

    const { code, stdout } = await hexlod(['regress', join(flights, `${name}.flight.json`), '--refs', refs, '--out', out]);
    assert.equal(code, 1, stdout);
    const t12 = doc.stats[12].triangles;
    // pixelmatch counts the block's pixels but for those of its outline that it takes for anti-aliasing.
    assert.match(stdout, new RegExp(`REGRESSION: mesh: 1 of 21 frames differ from the reference \\(frame 12: triangles ${t12} → ${t12 - 6}\\); frame 20: 1\\.[23]\\d % of pixels differ \\(0\\.200 % allowed\\)`));
    assert.match(stdout, /^ {4}frame 20: 7\d\d pixels \(1\.[23]\d %\) differ beyond threshold 0\.004, 115 \(0\.200 %\) allowed; 1\.39 % changed at all/m);
    assert.doesNotMatch(stdout, /frame 6:/); // the untouched capture still matches
    const diff = readPng(readFileSync(join(out, name, 'frame-0020-diff.png')));
    let red = 0, yellow = 0, marked = 0;
    for (let k = 0; k < diff.rgb.length; k += 3) {
      const isRed = diff.rgb[k] === 255 && diff.rgb[k + 1] === 0 && diff.rgb[k + 2] === 0;
      const isYellow = diff.rgb[k] === 255 && diff.rgb[k + 1] === 255 && diff.rgb[k + 2] === 0;
      red += isRed;
      yellow += isYellow;
      const p = k / 3, x = p % diff.width, y = Math.floor(p / diff.width);
      if ((isRed || isYellow) && x >= 100 && x < 140 && y >= 50 && y < 70) marked += 1;
    }
    assert.equal(marked, 800, 'the diff marks exactly the painted block');
    assert.equal(red + yellow, 800);
    assert.ok(red > 700, `${red} red pixels`);
    const report = readFileSync(join(out, 'report.html'), 'utf8');
    assert.match(report, /<h1>hexlod regress: 1 flight: 1 regressed<\/h1>/);
    for (const file of ['frame-0020-ref.png', 'frame-0020.png', 'frame-0020-diff.png']) assert.ok(report.includes(`${name}/${file}`), file);
    for (const label of ['reference', 'new', 'diff']) assert.match(report, new RegExp(`<figcaption>${label}</figcaption>`));
    assert.match(report, new RegExp(`<td class="d">${t12} → ${t12 - 6}</td>`)); // the figure table

    // The report's comparer: the slider at 100 % shows the reference (the magenta block), at 0 % the new image.
    const session = await startBrowser();
    try {
      const page = await session.browser.newPage({ viewport: { width: 1200, height: 900 } });
      await page.goto(`file://${join(out, 'report.html')}`);
      const compare = page.locator('.capture').nth(1).locator('.compare');
      const blockPixel = async (split) => {
        await page.locator('.capture').nth(1).locator('input[type=range]').first().fill(String(split));
        const shot = decode(await compare.screenshot());
        const k = shot.channels * ((1 + 60) * shot.width + 1 + 120); // the block's centre, inside the 1 px border
        return [shot.data[k], shot.data[k + 1], shot.data[k + 2]];
      };
      assert.deepEqual(await blockPixel(100), [255, 0, 255]);
      assert.notDeepEqual(await blockPixel(0), [255, 0, 255]);
    } finally {
      await session.close();
    }

    // A mask over the block (CSS pixels): the pixels pass, the figures still fail.
    const masked = await hexlod(['regress', join(flights, `${name}.flight.json`), '--refs', refs, '--out', out, '--mask', '100,50,40,20']);
    assert.equal(masked.code, 1);
    assert.doesNotMatch(masked.stdout, /frame 20: .* differ/);
    assert.match(masked.stdout, /frame 12: triangles/);
  } finally {
    rmSync(refs, { recursive: true, force: true });
  }
});

test('the canvas is viewport x dpr device pixels: 160 x 90 at dpr 2 flies as 320 x 180 at dpr 1, pixel for pixel', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-dpr-'));
  try {
    const name = 'volcano_down_tau1';
    const flight = JSON.parse(readFileSync(join(flights, `${name}.flight.json`), 'utf8'));
    assert.deepEqual([flight.viewport, flight.dpr], [[320, 180], 1]);
    Object.assign(flight, { viewport: [160, 90], dpr: 2, dem: join(flights, flight.dem) });
    writeFileSync(join(dir, `${name}.flight.json`), JSON.stringify(flight));
    // The references of the 320 x 180 flight at dpr 1.
    const { code, stdout } = await hexlod(['regress', join(dir, `${name}.flight.json`), '--refs', join(flights, 'refs'),
      '--out', join(dir, 'out'), '--strict']);
    assert.equal(code, 0, stdout);
    assert.match(stdout, /ok: 21 frames, 2 captures; pixels identical; the flight changed since the reference \(viewport 320x180 → 160x90, dpr 1 → 2\), its results did not$/m);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('the window API and URL parameters: ready, frame(n) in order, pixels, ops= and viewport= overrides, a bad flight named', async () => {
  const session = await startBrowser();
  try {
    const dem = session.files.addPath('api', 'dem', join(root, 'tests/fixtures/volcano_maungawhau.png'));
    const flight = session.files.addPath('api', 'flight', join(flights, 'volcano_down_tau1.flight.json'));
    const page = await session.browser.newPage({ viewport: { width: 400, height: 300 } });
    await page.goto(`${session.url}?src=${dem}&flight=${flight}&ops=3&viewport=200x100&dpr=1`);
    await page.waitForFunction(() => window.hexlod?.flight, null, { timeout: 120000 });
    const result = await page.evaluate(async () => {
      const api = window.hexlod.flight;
      const ready = await api.ready;
      const first = await api.frame(2, { pixels: true });
      const again = await api.frame(1); // drawn already: its figures at once
      const late = await api.frame(0, { pixels: true }).then(() => 'resolved', (e) => e.message);
      const outside = await api.frame(ready.frames).then(() => 'resolved', (e) => e.message);
      const canvas = document.getElementById('view');
      return { ready, stats: first.stats, size: [first.pixels.width, first.pixels.height], bytes: atob(first.pixels.base64).length,
        again: again.stats.frame, late, outside, done: api.done, all: api.stats(), canvas: [canvas.width, canvas.height] };
    });
    assert.deepEqual([result.ready.width, result.ready.height, result.ready.frames], [200, 100, 21]);
    assert.deepEqual(result.canvas, [200, 100]);
    assert.deepEqual(result.size, [200, 100]);
    assert.equal(result.bytes, 200 * 100 * 4);
    assert.equal(result.stats.frame, 2);
    assert.match(result.stats.hash, /^[0-9a-f]{16}$/);
    assert.equal(result.again, 1);
    assert.match(result.late, /frame 0 was drawn already/);
    assert.match(result.outside, /frame 21 is not in the flight \(0 to 20\)/);
    assert.equal(result.done, 3);
    assert.deepEqual(result.all.map((s) => s.frame), [0, 1, 2]);
    for (const s of result.all) assert.ok(s.operations <= 3, `ops=3 caps the operations per frame: ${s.operations}`);
    await page.close();

    // A flight with a bad key: the page stops with the message naming it.
    const badPath = join(mkdtempSync(join(tmpdir(), 'hexlod-badflight-')), 'bad.flight.json');
    writeFileSync(badPath, JSON.stringify({ keyframes: [{ time: 0, position: [0, 1, 0], target: [1, 0, 1], fov: 500 }] }));
    const bad = session.files.addPath('bad', 'flight', badPath);
    const badPage = await session.browser.newPage();
    await badPage.goto(`${session.url}?src=${dem}&flight=${bad}`);
    await badPage.waitForFunction(() => window.hexlod?.status === 'error', null, { timeout: 60000 });
    assert.match(await badPage.evaluate(() => window.hexlod.error), /bad\.flight\.json: "keyframes"\[0\]\.fov must be a number from 1 to 170/);
    await badPage.close();
    rmSync(dirname(badPath), { recursive: true, force: true });
  } finally {
    await session.close();
  }
});

/** A copy of what the page and the command need, with node_modules linked, to try a change to the page on.
 * src/api marks it a checkout, so regress serves the changed source rather than looking for a built page. */
function projectCopy() {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-copy-'));
  for (const part of ['bin', 'lib', 'web', 'shaders', 'public', 'src/api', 'build/wasm', 'build/wasm-diag', 'vite.config.js', 'package.json']) {
    cpSync(join(root, part), join(dir, part), { recursive: true });
  }
  symlinkSync(join(root, 'node_modules'), join(dir, 'node_modules'));
  return dir;
}

test('a subtle shader change (lowland red 0.14 → 0.15) fails by default; below a looser tolerance it passes and is reported as drift', async () => {
  const copy = projectCopy();
  try {
    const shader = join(copy, 'shaders/ground_color.glsl');
    const text = readFileSync(shader, 'utf8');
    assert.ok(text.includes('vec3 lowland = vec3(0.14, 0.19, 0.08);'), 'the lowland colour this test changes');
    writeFileSync(shader, text.replace('vec3(0.14, 0.19, 0.08)', 'vec3(0.15, 0.19, 0.08)'));
    const args = ['regress', flights, '--grep', '^(grandcanyon_tau1|volcano_down_tau4)$', '--out', join(copy, 'out')];
    const { code, stdout } = await hexlod(args, copy);
    assert.equal(code, 1, stdout);
    assert.match(stdout, /grandcanyon_tau1: REGRESSION: frame 6: \d+\.\d+ % of pixels differ \(0\.200 % allowed\); frame 20: /);
    assert.match(stdout, /volcano_down_tau4: REGRESSION: frame 6: /);
    assert.match(stdout, /the flight and its height field are as the reference recorded them: the difference comes from hexlod/);
    assert.doesNotMatch(stdout, /mesh:/); // a shader change leaves the meshes alone
    const loose = await hexlod([...args, '--threshold', '0.01'], copy);
    assert.equal(loose.code, 0, loose.stdout);
    assert.match(loose.stdout, /grandcanyon_tau1: ok: 21 frames, 2 captures; pixels changed below the tolerance: frame 6 \d+\.\d+ % changed at all, mean change 0\.\d+, largest \d of 255/);
  } finally {
    rmSync(copy, { recursive: true, force: true });
  }
});

test('a height field by URL flies in the page as the file does: the same figures and pixels as the references', async () => {
  const server = createServer((req, res) => {
    const path = join(root, 'tests/fixtures', req.url.replace(/^\//, ''));
    if (!existsSync(path)) return void res.writeHead(404).end();
    res.writeHead(200).end(readFileSync(path));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-url-'));
  try {
    const flight = JSON.parse(readFileSync(join(flights, 'volcano_down_tau4.flight.json'), 'utf8'));
    flight.dem = `http://127.0.0.1:${server.address().port}/volcano_maungawhau.png`;
    writeFileSync(join(dir, 'volcano_down_tau4.flight.json'), JSON.stringify(flight));
    const { code, stdout } = await hexlod(['regress', join(dir, 'volcano_down_tau4.flight.json'), '--refs', join(flights, 'refs'), '--out', join(dir, 'out'), '--strict']);
    assert.equal(code, 0, stdout);
    assert.match(stdout, /volcano_down_tau4: ok: 21 frames, 2 captures; pixels identical/);
  } finally {
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});

test('a folder flown in the browser: a bad flight and one without a reference fail alone, the other flies; JUnit, JSON and the report follow every run', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-folder-'));
  try {
    for (const name of ['volcano_down_tau1', 'volcano_down_tau4']) {
      const flight = JSON.parse(readFileSync(join(flights, `${name}.flight.json`), 'utf8'));
      flight.dem = join(flights, flight.dem);
      writeFileSync(join(dir, `${name}.flight.json`), JSON.stringify(flight));
    }
    cpSync(join(flights, 'refs/volcano_down_tau4'), join(dir, 'refs/volcano_down_tau4'), { recursive: true });
    writeFileSync(join(dir, 'typo.flight.json'), JSON.stringify({ keyframes: [{ time: 0, position: [0, 1, 0], target: [1, 0, 1] }], fsp: 10 }));
    const args = ['regress', dir, '--out', join(dir, 'out'), '--junit', join(dir, 'junit.xml'), '--json', join(dir, 'result.json')];
    const first = await hexlod(args);
    assert.equal(first.code, 2, first.stdout);
    assert.match(first.stdout, /\] typo: BAD INPUT: \S+typo\.flight\.json: "fsp" is not a flight key/);
    assert.match(first.stdout, /\] volcano_down_tau1: NO REFERENCE: no reference in \S+; make one with: hexlod regress \S+volcano_down_tau1\.flight\.json --update/);
    assert.match(first.stdout, /\] volcano_down_tau4: ok: 21 frames, 2 captures; pixels identical/);
    assert.match(first.stdout, /^hexlod regress: 3 flights: 1 had bad input, 1 had no reference, 1 passed$/m);
    const json = JSON.parse(readFileSync(join(dir, 'result.json'), 'utf8'));
    assert.deepEqual(json.flights.map((f) => f.verdict), ['bad-input', 'no-reference', 'pass']);
    assert.equal(json.flights[2].captures[1].changed, 0);
    assert.ok(existsSync(join(dir, 'out/volcano_down_tau4/frame-0020-diff.png')));
    assert.ok(!existsSync(join(dir, 'out/volcano_down_tau1')), 'a flight without a reference is not flown');

    // The next run cannot start its browser: exit 3, and every report says so, none shows the run before.
    const second = await hexlod([...args, '--grep', 'tau4', '--chromium', '/bin/false']);
    assert.equal(second.code, 3, second.stdout);
    assert.match(second.stderr, /^hexlod: Chromium at \/bin\/false did not start: the program exited at once; is it a Chromium browser\?\n$/);
    const summary = readFileSync(join(dir, 'out/summary.txt'), 'utf8');
    assert.match(summary, /^hexlod regress: 1 flight: 1 could not run; stopped: Chromium at \/bin\/false did not start/);
    assert.doesNotMatch(summary, /passed|typo/);
    assert.match(readFileSync(join(dir, 'out/report.html'), 'utf8'), /<h2>volcano_down_tau4: could not run<\/h2>/);
    assert.equal(JSON.parse(readFileSync(join(dir, 'result.json'), 'utf8')).exitCode, 3);
    assert.match(readFileSync(join(dir, 'junit.xml'), 'utf8'), /<testcase classname="hexlod.regress" name="volcano_down_tau4"[^>]*>\s*<error type="error" message="Chromium at \/bin\/false did not start/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('a flight that names an image, or its image layers (files or web map tiles), drapes them before its first frame: their colours at projected ground points, a hidden one unseen, tiles waited for; a refused image fails the flight', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-image-flight-'));
  try {
    // Straight down from 3200 km over the middle of the default terrain, north up, unlit so
    // the pixels are the image's colours, on the flat Earth, where the test's own camera
    // (below) projects the ground points. Both files are named relative to the flight file.
    const { width, height, cell_size_x_m: spacingX, cell_size_y_m: spacingY } = JSON.parse(readFileSync(join(root, 'public/terrain/globe_himalaya_2048.json'), 'utf8'));
    const centre = [((width - 1) * spacingX) / 2, ((height - 1) * spacingY) / 2];
    const flight = {
      dem: relative(dir, join(root, 'public/terrain/globe_himalaya_2048.png')),
      image: relative(dir, join(root, 'tests/fixtures/imagery/bmng_himalaya_4arcmin.jpg')),
      viewport: [400, 400],
      settings: { exaggeration: 1, imageUnlit: true, imageOpacity: 1, earth: 'flat' },
      keyframes: [{ time: 0, position: [centre[0], 3.2e6, centre[1]], target: [centre[0], 0, centre[1]] }],
    };
    writeFileSync(join(dir, 'draped.flight.json'), JSON.stringify(flight));
    const refs = join(dir, 'refs'), out = join(dir, 'out');
    const { code, stdout, stderr } = await hexlod(['regress', join(dir, 'draped.flight.json'), '--update', '--refs', refs, '--out', out]);
    assert.equal(code, 0, `${stdout}\n${stderr}`);
    const frame = readPng(readFileSync(join(refs, 'draped/frame-0000.png')));

    // The camera of frame 0 as the page poses it (near and far do not move a point on screen).
    const parsed = parseFlight(flight, 'draped.flight.json');
    const terrain = { width, height, spacingX, spacingY, minHeight: 0, maxHeight: 8752, heightAt: () => 0 };
    const flightCamera = new FlightCamera(parsed, terrain, 400, 400);
    flightCamera.at(0);
    const camera = new ScriptedCamera();
    camera.pose(flightCamera);
    camera.update(1);
    for (const [name, [lon, lat, expected]] of Object.entries(BLUE_MARBLE_POINTS)) {
      const at = screenPoint(camera.viewProjection, groundPoint(lon, lat, spacingX, spacingY), 400, 400);
      assert.ok(at.every((v) => v > 0 && v < 400), `${name} is on screen at ${at}`);
      const got = colourAt({ width: frame.width, data: frame.rgb, channels: 3 }, at);
      assert.ok(coloursMatch(got, expected, 24), `${name} at ${at}: ${got}, the image has ${expected}`);
    }

    // Layers named by the flight, bottom first: the Blue Marble in Web Mercator (reprojected
    // onto the geographic terrain), and over it a magenta picture the flight hides.
    writeFileSync(join(dir, 'magenta.png'), encode({ width: 4, height: 4, data: new Uint8Array(48).map((_, i) => [255, 0, 255][i % 3]), channels: 3 }));
    writeFileSync(join(dir, 'layers.flight.json'), JSON.stringify({ ...flight, image: undefined, layers: [
      { image: relative(dir, join(root, 'tests/fixtures/reprojection/bmng_himalaya_3857.tif')) },
      { image: 'magenta.png', visible: false }] }));
    const layered = await hexlod(['regress', join(dir, 'layers.flight.json'), '--update', '--refs', refs, '--out', out]);
    assert.equal(layered.code, 0, `${layered.stdout}\n${layered.stderr}`);
    const layeredFrame = readPng(readFileSync(join(refs, 'layers/frame-0000.png')));
    for (const [name, [lon, lat, expected]] of Object.entries(BLUE_MARBLE_POINTS)) {
      const at = screenPoint(camera.viewProjection, groundPoint(lon, lat, spacingX, spacingY), 400, 400);
      const got = colourAt({ width: layeredFrame.width, data: layeredFrame.rgb, channels: 3 }, at);
      assert.ok(coloursMatch(got, expected, 24), `layers: ${name} at ${at}: ${got}, the image has ${expected}`);
    }

    // A layer of web map tiles from a server with latency: each frame waits for its tiles, so
    // a second run matches the references made by the first.
    const server = await startTileServer(join(root, 'tests/fixtures/webtiles/bmng'), { latencyMs: 30 });
    try {
      writeFileSync(join(dir, 'tiles.flight.json'), JSON.stringify({ ...flight, image: undefined,
        layers: [{ tiles: `${server.url}/{z}/{x}/{y}.png|zoom=3-7` }] }));
      const made = await hexlod(['regress', join(dir, 'tiles.flight.json'), '--update', '--refs', refs, '--out', out]);
      assert.equal(made.code, 0, `${made.stdout}\n${made.stderr}`);
      const tiled = readPng(readFileSync(join(refs, 'tiles/frame-0000.png')));
      const points = JSON.parse(readFileSync(join(root, 'tests/fixtures/webtiles/bmng_points.json'), 'utf8')).points.filter((p) => p.name !== 'Khumbu snow');
      for (const p of points) {
        const at = screenPoint(camera.viewProjection, groundPoint(p.lon, p.lat, spacingX, spacingY), 400, 400);
        const got = colourAt({ width: tiled.width, data: tiled.rgb, channels: 3 }, at);
        assert.ok(coloursMatch(got, p.z7.rgba.slice(0, 3), 16), `tiles: ${p.name} at ${at}: ${got}, GDAL's tiles have ${p.z7.rgba}`);
      }
      assert.ok(server.tilesRequested().length > 0);
      const again = await hexlod(['regress', join(dir, 'tiles.flight.json'), '--refs', refs, '--out', out]);
      assert.equal(again.code, 0, `the second run matches the first: ${again.stdout}\n${again.stderr}`);
    } finally {
      await server.close();
    }

    // The Haiti orthophoto is in UTM: the flight fails with the image's own message.
    writeFileSync(join(dir, 'refused.flight.json'), JSON.stringify({ ...flight,
      image: relative(dir, join(root, 'tests/fixtures/imagery/haiti_rgb_5m_tiled_deflate.tif')) }));
    const refused = await hexlod(['regress', join(dir, 'refused.flight.json'), '--update', '--refs', refs, '--out', out]);
    assert.equal(refused.code, 1, `${refused.stdout}\n${refused.stderr}`);
    assert.match(refused.stdout, /haiti_rgb_5m_tiled_deflate\.tif: it lies outside the terrain/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
