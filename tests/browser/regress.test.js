// Our own regression flights (tests/regress/flights) through `hexlod regress`: every flight flown
// in headless Chromium gives the mesh hashes and figures of its Node replay and of the stored
// references, and pixels within the tolerance. A changed reference is caught: a painted block
// in an image shows up in the diff, a changed triangle count in the figures, exit code 1.
// References are rewritten with: node bin/hexlod.js regress tests/regress/flights --update
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { readPng, writePng } from '../../bin/regress_compare.js';
import { startBrowser } from '../../bin/regress_browser.js';

const root = fileURLToPath(new URL('../../', import.meta.url));
const flights = join(root, 'tests/regress/flights');
const outDir = join(root, 'tests/out/regress');

function hexlod(args) {
  return new Promise((resolve) => {
    execFile(process.execPath, [join(root, 'bin/hexlod.js'), ...args], { cwd: root, timeout: 600000, maxBuffer: 16 << 20 },
      (error, stdout, stderr) => resolve({ code: error ? error.code : 0, stdout, stderr }));
  });
}

test('every regression flight matches Node and its references, hashes exactly and pixels within the tolerance', async () => {
  const names = readdirSync(flights).filter((f) => f.endsWith('.flight.json')).map((f) => f.replace('.flight.json', ''));
  const { code, stdout, stderr } = await hexlod(['regress', flights, '--out', outDir]);
  assert.equal(code, 0, `${stdout}\n${stderr}`);
  for (const name of names) assert.match(stdout, new RegExp(`\\] ${name}: ok \\(21 frames`), `${name}\n${stdout}`);
  assert.match(stdout, new RegExp(`${names.length} flights, 0 regressed`));
  const report = readFileSync(join(outDir, 'report.html'), 'utf8');
  assert.match(report, /all \d+ flights as the references/);
  assert.ok(existsSync(join(outDir, 'grandcanyon_tau1/frame-0020-diff.png')));
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
    assert.match(stdout, /REGRESSION: frame 12: triangles \d+, the reference has \d+/);
    assert.match(stdout, /frame 20: 1\.389 % of pixels differ/);
    assert.doesNotMatch(stdout, /frame 6:/); // the untouched capture still matches
    const diff = readPng(readFileSync(join(out, name, 'frame-0020-diff.png')));
    let red = 0;
    for (let k = 0; k < diff.rgb.length; k += 3) if (diff.rgb[k] === 255 && diff.rgb[k + 1] === 0 && diff.rgb[k + 2] === 0) red += 1;
    assert.equal(red, 800, 'the diff marks exactly the painted block');
    const report = readFileSync(join(out, 'report.html'), 'utf8');
    assert.match(report, /1 of 1 flights regressed/);
    for (const file of ['frame-0020-ref.png', 'frame-0020.png', 'frame-0020-diff.png']) assert.ok(report.includes(`${name}/${file}`), file);
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
      '--out', join(dir, 'out'), '--threshold', '0', '--max-share', '0']);
    assert.equal(code, 0, stdout);
    assert.match(stdout, /ok \(21 frames, 2 captures, largest pixel difference 0\)/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('the window API and URL parameters: ready, frame(n) in order, pixels, ops= and viewport= overrides, a bad flight named', async () => {
  const session = await startBrowser();
  try {
    const dem = session.files.add('api', 'dem', join(root, 'tests/fixtures/volcano_maungawhau.png'));
    const flight = session.files.add('api', 'flight', join(flights, 'volcano_down_tau1.flight.json'));
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
    const bad = session.files.add('bad', 'flight', badPath);
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
