// A Cloud-Optimized GeoTIFF opened in the page by streaming: by ?src= from a server that honours
// Range (lib/range_server.js, with latency), and dropped as a File (read by slices). The view
// fills in without input, fetches less than the file, says what it waits for, and once nothing
// is awaited looks like the same file loaded whole; the mesh stays watertight. Faults leave the
// terrain on screen and say what went wrong. Fixtures: tests/fixtures/cog/README.md.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decode } from 'fast-png';
import pixelmatch from 'pixelmatch';
import { startViewer, openPage, pageReady, dropFiles, terrainShown, terrainCoverage, outDir, projectDir } from '../../lib/page_harness.js';
import { startRangeServer } from '../../lib/range_server.js';

const COGS = `${projectDir}tests/fixtures/cog/`;
const HIMALAYA = 'himalaya_1024_i16.tif'; // 1024², 256² tiles, overviews 512² and 256²
const SMALL = 'jacksboro_403x344_f32_no_overviews.tif';
const STRIPS = 'jacksboro_403x344_f32_strips.tif';
const VIEWPORT = { width: 480, height: 300 }; // small: SwiftShader draws each frame on the CPU
// A budget the frames of SwiftShader can keep, and an error that the overviews meet in part
// of the opening view, so it needs some of the full-resolution tiles and not all.
const OPTIONS = 'budget=50&tau=3';
const HIDE_BOXES = '#hud, #side, #drop-hint, #status, #intake, #panel { display: none !important; }';

let viewer, ranged, whole, tmp;
before(async () => {
  tmp = mkdtempSync(join(tmpdir(), 'hexlod-streaming-'));
  const bytes = readFileSync(COGS + HIMALAYA);
  writeFileSync(join(tmp, HIMALAYA), bytes);
  for (const name of [SMALL, STRIPS]) writeFileSync(join(tmp, name), readFileSync(COGS + name));
  // Cut inside the image directories: no reader can open it.
  writeFileSync(join(tmp, 'cut_header.tif'), bytes.subarray(0, 600));
  // Cut inside the last full-resolution tiles (a COG stores them last, row by row): it opens,
  // and the south-east tiles lie past its end.
  writeFileSync(join(tmp, 'cut_tiles.tif'), bytes.subarray(0, Math.round(0.9 * bytes.length)));
  [viewer, ranged, whole] = await Promise.all([startViewer(), startRangeServer(tmp, { latencyMs: 20 }),
    startRangeServer(tmp, { range: false })]);
});
after(async () => {
  await Promise.all([viewer?.close(), ranged?.close(), whole?.close()]);
  rmSync(tmp, { recursive: true, force: true });
});

/** Records every HUD tiles line the page shows, from its first frame on. */
const recordHud = (page) => page.addInitScript(() => {
  window.hudLines = [];
  const poll = () => {
    const line = window.hexlod?.hud?.tiles;
    if (line && window.hudLines.at(-1) !== line) window.hudLines.push(line);
    window.sawProvisional ||= /\(provisional\)/.test(document.querySelector('#hud .hud-summary')?.textContent ?? '');
    requestAnimationFrame(poll);
  };
  requestAnimationFrame(poll);
});

/** Waits until no tile is awaited and the mesh has converged. */
const settled = (page) => page.waitForFunction(() => window.hexlod.converged && window.hexlod.tiles?.settled
  && window.hexlod.hud?.errorProvisional === false, null, { timeout: 120000, polling: 100 });

/**
 * Every edge of the drawn mesh between two triangles, or on the mesh's one outer boundary: the
 * edges used once must form a single closed loop (a crack or a T-junction would make another).
 * Vertices are matched by their ground position; degenerate triangles are left out.
 */
async function meshEdges(page) {
  const { indices, positions, stride } = await page.evaluate(() => {
    const s = window.hexlod.terrainObject().stream();
    return { indices: Array.from(s.indices), positions: Array.from(s.vertices), stride: s.vertices.length / s.vertexCount };
  });
  const key = (i) => `${positions[i * stride]},${positions[i * stride + 2]}`;
  const edges = new Map();
  let triangles = 0;
  for (let k = 0; k + 2 < indices.length; k += 3) {
    const v = [key(indices[k]), key(indices[k + 1]), key(indices[k + 2])];
    if (v[0] === v[1] || v[1] === v[2] || v[0] === v[2]) continue;
    triangles += 1;
    for (let e = 0; e < 3; e++) {
      const a = v[e], b = v[(e + 1) % 3], id = a < b ? `${a}|${b}` : `${b}|${a}`;
      edges.set(id, (edges.get(id) ?? 0) + 1);
    }
  }
  const overused = [...edges.values()].filter((n) => n > 2).length;
  const boundary = [...edges].filter(([, n]) => n === 1).map(([id]) => id.split('|'));
  // Walk the boundary edges from one vertex: one loop visits them all.
  const next = new Map();
  for (const [a, b] of boundary) {
    next.set(a, [...(next.get(a) ?? []), b]);
    next.set(b, [...(next.get(b) ?? []), a]);
  }
  const oddVertices = [...next.values()].filter((list) => list.length !== 2).length;
  const seen = new Set();
  const stack = boundary.length ? [boundary[0][0]] : [];
  while (stack.length) {
    const v = stack.pop();
    if (seen.has(v)) continue;
    seen.add(v);
    stack.push(...next.get(v));
  }
  return { triangles, edges: edges.size, overused, boundaryEdges: boundary.length, oddVertices, loopCovers: seen.size === next.size };
}

/** The canvas alone as decoded PNG, saved under tests/out. */
async function canvasShot(page, name) {
  await page.addStyleTag({ content: HIDE_BOXES });
  await page.evaluate(() => new Promise((resolve) => {
    const start = window.hexlod.frames;
    window.hexlod.requestRender();
    const poll = () => (window.hexlod.frames > start ? resolve() : requestAnimationFrame(poll));
    poll();
  }));
  return decode(await page.screenshot({ path: `${outDir}/${name}.png` }));
}

test('?src= of a COG streams: tiles fill in unasked, less than the file is fetched, the whole file\'s view, watertight', async () => {
  const url = `${ranged.url}/${HIMALAYA}`;
  const opened = await openPage(viewer.browser, 'about:blank', VIEWPORT);
  const { page, problems } = opened;
  await recordHud(page);
  // Hill shading: light from the surface's normals alone. The natural colours also follow the
  // height range, which for a COG without statistics is its overviews' until finer tiles come.
  await page.goto(`${viewer.url}?${OPTIONS}&shading=hillshade&src=${encodeURIComponent(url)}`);
  await pageReady(page);
  const first = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error, terrain: window.hexlod.terrain }));
  assert.equal(first.status, 'ready', first.error);
  assert.deepEqual([first.terrain.name, first.terrain.width, first.terrain.height, first.terrain.tiled], [HIMALAYA, 1024, 1024, true]);
  await settled(page);
  const figures = await page.evaluate(() => ({ ...window.hexlod.tiles, hud: window.hexlod.hud, lines: window.hudLines,
    sawProvisional: window.sawProvisional }));
  console.log(`streamed: ${figures.tilesIn} tiles in, ${figures.bytesFetched} of ${figures.fileBytes} bytes fetched, ` +
    `${figures.heldBytes} bytes of samples held; HUD: ${figures.lines.join(' → ')}`);
  assert.equal(figures.fileBytes, readFileSync(COGS + HIMALAYA).length);
  assert.ok(figures.tilesIn > 0, 'tiles came in after the coarsest level, with no input');
  assert.ok(figures.bytesFetched < figures.fileBytes, `${figures.bytesFetched} of ${figures.fileBytes} bytes fetched`);
  assert.deepEqual(figures.failures, []);
  assert.ok(figures.lines.some((line) => /^waiting for \d+ tiles? · [\d.]+ of 1\.5 MB fetched/.test(line)), figures.lines.join('\n'));
  assert.match(figures.hud.tiles, /^all tiles in view loaded/);
  assert.ok(figures.sawProvisional, 'while tiles were awaited, the error was marked provisional');
  assert.equal(figures.hud.errorProvisional, false);
  assert.doesNotMatch(await page.locator('#hud').innerText(), /provisional/);

  const mesh = await meshEdges(page);
  console.log(`mesh: ${JSON.stringify(mesh)}`);
  assert.ok(mesh.triangles > 1000, `${mesh.triangles} triangles`);
  assert.equal(mesh.overused, 0, 'no edge is shared by more than two triangles');
  assert.equal(mesh.oddVertices, 0, 'every boundary vertex joins two boundary edges');
  assert.ok(mesh.loopCovers, 'the edges used once form one loop: the outer boundary');

  // The pointer readout's height comes from the tiles.
  const height = await page.evaluate(() => {
    const t = window.hexlod.terrainObject();
    return t.heightAt(0.5 * (t.width - 1) * t.spacingX, 0.5 * (t.height - 1) * t.spacingY);
  });
  assert.ok(Number.isFinite(height) && height > 0, `height at the centre ${height}`);
  await page.mouse.move(VIEWPORT.width / 2, VIEWPORT.height / 2);
  await page.waitForFunction(() => window.hexlod.cursor !== null, null, { timeout: 10000 });
  assert.match(await page.locator('#hud').innerText(), /cursor {2}x [\d.]+ km {2}z [\d.]+ km {2}height [\d.]+ m/);

  await page.evaluate(() => window.hexlod.flushUrl());
  const search = new URL(page.url()).searchParams;
  const streamed = await canvasShot(page, 'streaming-src');
  // A tile request the view no longer needs is aborted, which the browser logs as failed.
  assert.deepEqual(problems.filter((p) => p !== `request failed: ${url}`), []);
  await page.close();

  // The same file, same camera, loaded whole: a server without Range falls back to a whole load.
  // Its field textures would shade from the full field; the streamed view has the mesh's normals
  // only, so the whole load is told to shade alike.
  search.set('src', `${whole.url}/${HIMALAYA}`);
  const other = await openPage(viewer.browser, `${viewer.url}?${search}`, VIEWPORT);
  await pageReady(other.page);
  const loaded = await other.page.evaluate(() => ({ error: window.hexlod.error, terrain: window.hexlod.terrain }));
  assert.equal(loaded.terrain?.tiled, false, `loaded whole: ${loaded.error}`);
  await other.page.evaluate(() => {
    for (const [key, value] of [['normals', 'mesh'], ['shadows', false], ['occlusion', false]]) window.hexlod.setSetting(key, value);
  });
  await other.page.waitForFunction(() => window.hexlod.converged, null, { timeout: 120000 });
  const reference = await canvasShot(other.page, 'streaming-whole');
  const { width, height: rows } = streamed;
  const diff = new Uint8Array(width * rows * 4);
  const rgba = (png) => (png.channels === 4 ? png.data : Uint8Array.from({ length: width * rows * 4 }, (_, k) => (k % 4 === 3 ? 255 : png.data[(k >> 2) * 3 + (k % 4)])));
  const differing = pixelmatch(rgba(streamed), rgba(reference), diff, width, rows, { threshold: 0.1 });
  console.log(`streamed vs whole: ${differing} of ${width * rows} pixels differ; whole heights ` +
    `${loaded.terrain.minHeight} … ${loaded.terrain.maxHeight}, streamed ${first.terrain.minHeight} … ${first.terrain.maxHeight}`);
  // Where the view needs the full resolution, both meshes read the same samples; elsewhere the
  // streamed one may rest on an overview's samples within the error bound τ: a few pixels along
  // ridges, never a region. 1 % is well above that and far below a missing or misplaced tile.
  assert.ok(differing < 0.01 * width * rows, `${differing} pixels differ`);
  // The reader's first request found no Range support and cut the answer off; the optional
  // sidecar himalaya_1024_i16.json is not there (404).
  assert.deepEqual(other.problems.filter((p) => p !== `request failed: ${whole.url}/${HIMALAYA}` && !/404/.test(p)), []);
  await other.page.close();
});

test('a dropped COG streams from the File, never read whole, and shows terrain; other TIFFs load whole', async () => {
  const { page, problems } = await openPage(viewer.browser, 'about:blank', VIEWPORT);
  // Every whole-Blob read on the page's thread, by size (the workers read their slices).
  await page.addInitScript(() => {
    window.blobReads = [];
    for (const method of ['arrayBuffer', 'text', 'stream']) {
      const original = Blob.prototype[method];
      Blob.prototype[method] = function (...args) {
        window.blobReads.push(this.size);
        return original.apply(this, args);
      };
    }
  });
  await page.goto(`${viewer.url}?${OPTIONS}&src=${encodeURIComponent(`${ranged.url}/${SMALL}`)}`);
  await pageReady(page);
  const bytes = readFileSync(COGS + HIMALAYA);
  await dropFiles(page, [{ name: HIMALAYA, bytes }]);
  await terrainShown(page, HIMALAYA);
  await settled(page);
  const { tiles, terrain, reads } = await page.evaluate(() => ({ tiles: window.hexlod.tiles, terrain: window.hexlod.terrain, reads: window.blobReads }));
  console.log(`dropped: ${tiles.tilesIn} tiles in; blob reads on the page: ${reads.join(', ')} bytes`);
  assert.equal(terrain.tiled, true);
  assert.equal(tiles.fileBytes, bytes.length);
  assert.ok(tiles.tilesIn > 0);
  assert.ok(reads.every((size) => size < bytes.length), `a read of the whole file: ${reads}`);
  const seen = await terrainCoverage(page);
  assert.ok(seen.coverage > 0.2 && seen.colours > 30, JSON.stringify(seen));

  // A small TIFF without overviews, tiled or in strips, loads whole as before.
  for (const name of [SMALL, STRIPS]) {
    await dropFiles(page, [{ name, bytes: readFileSync(COGS + name) }]);
    await terrainShown(page, name);
    assert.equal(await page.evaluate(() => window.hexlod.terrain.tiled), false, `${name} loads whole`);
  }
  // By ?src=, a TIFF in strips cannot stream: it loads whole.
  const outcome = await page.evaluate((url) => window.hexlod.openUrl(url), `${ranged.url}/${STRIPS}`);
  assert.equal(outcome, 'shown', await page.evaluate(() => window.hexlod.error));
  assert.equal(await page.evaluate(() => window.hexlod.terrain.tiled), false);
  assert.deepEqual(problems.filter((p) => !/404/.test(p)), []); // the strips' sidecar .json is not there
  await page.close();
});

test('faults: each says what went wrong, and the terrain on screen stays', async () => {
  const { page } = await openPage(viewer.browser, `${viewer.url}?${OPTIONS}&tilecache=1&src=${encodeURIComponent(`${ranged.url}/${SMALL}`)}`, VIEWPORT);
  await pageReady(page);
  await settled(page);
  const before = await page.evaluate(() => window.hexlod.terrain);
  assert.equal(before.name, SMALL);
  const open = (url) => page.evaluate(async (u) => {
    const outcome = await window.hexlod.openUrl(u);
    return { outcome, error: window.hexlod.error, status: document.getElementById('status').textContent, terrain: window.hexlod.terrain };
  }, url);
  const stays = async (what, result, pattern) => {
    console.log(`${what}: ${result.status}`);
    assert.equal(result.outcome, 'failed', what);
    assert.match(result.status, pattern, what);
    assert.deepEqual(result.terrain, before, `${what}: the terrain stays`);
    assert.equal(await page.evaluate(() => window.hexlod.settings.tileCacheMB), 1, `${what}: the settings stay`);
  };
  await stays('404', await open(`${ranged.url}/missing.tif`), /missing\.tif: cannot stream it .*HTTP 404/);
  // No Range, and 1.5 MB over the 1 MB cap: not loaded whole either.
  await stays('no Range, over the cap', await open(`${whole.url}/${HIMALAYA}`),
    /1\.5 MB, more than the 1 MB tile cache.*ignores Range.*gdal_translate -of COG/);
  await stays('truncated', await open(`${ranged.url}/cut_header.tif`), /cut_header\.tif: cannot stream it .*(truncated|TIFF)/i);
  const seen = await terrainCoverage(page);
  assert.ok(seen.coverage > 0.1, `the terrain is still drawn: ${JSON.stringify(seen)}`);

  // The cap setting: refused out of range, else applied to the open stream.
  for (const bad of [0, 'lots', 10000]) {
    assert.equal(await page.evaluate((v) => window.hexlod.setSetting('tileCacheMB', v), bad), false, `tilecache ${bad} refused`);
  }
  assert.match(await page.locator('#status').innerText(), /tilecache=10000 is not a number from 1 to 4096/);
  assert.equal(await page.evaluate(() => window.hexlod.settings.tileCacheMB), 1);
  assert.equal(await page.evaluate(() => window.hexlod.setSetting('tileCacheMB', 64)), true);
  await page.waitForFunction(() => window.hexlod.tiles.capBytes === 64 * 2 ** 20, null, { timeout: 10000, polling: 50 });

  // Tiles that fail once the file is open: a closer view asks for them; what is drawn stays,
  // and the HUD says why.
  /** Looks closely at (fx, fz) of the field and waits for a failed tile; returns the HUD's line. */
  const failsNear = async (what, fx, fz, kind) => {
    await page.evaluate(([x, z]) => {
      const orbit = window.hexlod.rig.cameras.orbit, t = window.hexlod.terrainObject();
      orbit.target[0] = x * (t.width - 1) * t.spacingX;
      orbit.target[2] = z * (t.height - 1) * t.spacingY;
      orbit.distance *= 0.15;
      window.hexlod.requestRender();
    }, [fx, fz]);
    await page.waitForFunction(() => window.hexlod.tiles?.failures.length > 0, null, { timeout: 60000 });
    const failed = await page.evaluate(() => ({ failures: window.hexlod.tiles.failures, line: window.hexlod.hud.tiles }));
    console.log(`${what}: ${failed.line}`);
    assert.equal(failed.failures[0].kind, kind, what);
    assert.match(await page.locator('#hud .hud-tiles').innerText(), new RegExp(`\\d+ tiles? failed \\(${kind}\\)`), what);
    const drawn = await terrainCoverage(page);
    assert.ok(drawn.coverage > 0.3 && drawn.colours > 20, `${what}: the terrain is still drawn: ${JSON.stringify(drawn)}`);
    await page.screenshot({ path: `${outDir}/streaming-failed-${kind}.png` });
    return failed.line;
  };
  assert.equal((await open(`${ranged.url}/cut_tiles.tif`)).outcome, 'shown');
  assert.match(await failsNear('tiles past the end', 0.85, 0.9, 'truncated'), /past the end of the file .*truncated/);
  // Its server answers 404 to everything once the file is open.
  assert.equal((await open(`${ranged.url}/${HIMALAYA}`)).outcome, 'shown');
  ranged.options.failPaths = [`/${HIMALAYA}`];
  try {
    assert.match(await failsNear('tiles failing mid-flight', 0.8, 0.3, 'http'), /HTTP 404/);
  } finally {
    ranged.options.failPaths = {};
  }
  await page.close();
});
