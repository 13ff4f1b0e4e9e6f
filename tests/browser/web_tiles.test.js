// Web map tiles on a real WebGL2 context (SwiftShader): web/render/shading/web_tile_textures.js
// with the Blue Marble tiles of tests/fixtures/webtiles/ (README there), read back through a
// shader that looks tiles up as the drape shader will (the recipe in web_tile_textures.js).
// The ground points show GDAL's colours of the zoom 4 tiles, then of the zoom 7 tiles once
// those are put, and of zoom 4 again once those are evicted; a coarser tile put later never
// hides a finer one; an evicted tile's entries fall back to its ancestor while its descendants
// keep theirs; the table on the GPU is its CPU copy; pages hold the decoded tiles and their
// mipmaps the 2 × 2 means. Then web/webtiles/web_tile_layer.js fetches from lib/tile_server.js
// on another origin, as a page fetches from a tile service: the base level and the view's
// tiles arrive, and a server that refuses cross-origin reads, one that is down and one whose
// tiles are missing each give one message of their own kind.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { mat4 } from 'gl-matrix';
import { decode } from 'fast-png';
import { startViewer, openPage, projectDir } from '../../lib/page_harness.js';
import { startTileServer } from '../../lib/tile_server.js';

const FIXTURES = `${projectDir}tests/fixtures/webtiles/`;
const POINTS = JSON.parse(readFileSync(`${FIXTURES}bmng_points.json`, 'utf8')).points;
// The Blue Marble image's extent (cell edges, degrees).
const IMAGE = { west: 72.9333, east: 90.0, north: 37.9333, south: 20.8 };
let viewer, server;

before(async () => {
  [viewer, server] = await Promise.all([startViewer(), startTileServer(`${FIXTURES}bmng`, { latencyMs: 5 })]);
});
after(async () => Promise.all([viewer?.close(), server?.close()]));

/** A page of the dev server (a fixture file) to import the modules into, without the viewer. */
async function modulePage() {
  const { page } = await openPage(viewer.browser, `${viewer.url}${viewer.fixturesUrl.slice(1)}webtiles/README.md`);
  return page;
}

const near = (a, b, tolerance) => a.length === b.length && a.every((v, i) => Math.abs(v - b[i]) <= tolerance);

test('tiles on the GPU: the finest loaded shows at each ground point, eviction falls back to the ancestor', async () => {
  const page = await modulePage();
  const result = await page.evaluate(async ({ web, tiles, points, image }) => {
    const { WebTileTextures } = await import(`${web}render/shading/web_tile_textures.js`);
    const { tableRange } = await import(`${web}webtiles/table_range.js`);
    const { lonLatToWorld } = await import(`${web}webtiles/web_mercator.js`);
    const canvas = document.createElement('canvas');
    canvas.width = 16; canvas.height = 1;
    const gl = canvas.getContext('webgl2', { antialias: false });
    const bitmap = async (z, x, y) => createImageBitmap(await (await fetch(`${tiles}${z}/${x}/${y}.png`)).blob(),
      { premultiplyAlpha: 'none', colorSpaceConversion: 'default' });

    // The lookup of the drape shader, for points given as tile coordinates t at the table's zoom.
    const compile = (type, source) => {
      const shader = gl.createShader(type);
      gl.shaderSource(shader, source);
      gl.compileShader(shader);
      if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
      return shader;
    };
    const program = gl.createProgram();
    gl.attachShader(program, compile(gl.VERTEX_SHADER, `#version 300 es
      void main() { gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0); }`));
    gl.attachShader(program, compile(gl.FRAGMENT_SHADER, `#version 300 es
      precision highp float; precision highp int;
      uniform highp usampler2D uTable;
      uniform highp sampler2DArray uPages;
      uniform ivec2 uOrigin;   // (x0, y0) of the table
      uniform int uZoom;       // its zoom Z
      uniform ivec2 uSize;     // its width and height
      uniform vec2 uT[16];     // per output pixel: tile coordinates at zoom Z relative to (x0, y0)
      out vec4 colour;
      void main() {
        vec2 t = uT[int(gl_FragCoord.x)];
        ivec2 cell = ivec2(floor(t));
        colour = vec4(0.0);
        if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, uSize))) return;
        uvec2 e = texelFetch(uTable, cell, 0).rg;
        if (e.r == 0u) return;
        int k = uZoom - int(e.g);
        ivec2 tile = (cell + uOrigin) >> k;
        vec2 uv = (t - vec2((tile << k) - uOrigin)) / exp2(float(k));
        colour = textureGrad(uPages, vec3(uv, float(e.r - 1u)), vec2(0.0), vec2(0.0));
      }`));
    gl.linkProgram(program);
    const target = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, target);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA8, 16, 1);
    const output = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, output);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);

    const textures = new WebTileTextures(gl, { memoryBytes: 1 }); // the least: 16 pages
    const range = tableRange([lonLatToWorld(image.west, 0)[0], lonLatToWorld(0, image.north)[1],
      lonLatToWorld(image.east, 0)[0], lonLatToWorld(0, image.south)[1]], 7);
    textures.setRange(range);

    /** The colours the lookup gives at the centres of the pixels of zoom `z` of GDAL's points. */
    const sample = (z) => {
      const t = new Float32Array(32);
      points.forEach((p, i) => {
        const scale = 2 ** (range.zoom - z) / 256;
        t[2 * i] = (p[`z${z}`].pixel[0] + 0.5) * scale - range.x0;
        t[2 * i + 1] = (p[`z${z}`].pixel[1] + 0.5) * scale - range.y0;
      });
      gl.useProgram(program);
      textures.bind(0, 1);
      gl.uniform1i(gl.getUniformLocation(program, 'uPages'), 0);
      gl.uniform1i(gl.getUniformLocation(program, 'uTable'), 1);
      gl.uniform2i(gl.getUniformLocation(program, 'uOrigin'), range.x0, range.y0);
      gl.uniform1i(gl.getUniformLocation(program, 'uZoom'), range.zoom);
      gl.uniform2i(gl.getUniformLocation(program, 'uSize'), range.width, range.height);
      gl.uniform2fv(gl.getUniformLocation(program, 'uT'), t);
      gl.bindFramebuffer(gl.FRAMEBUFFER, output);
      gl.viewport(0, 0, 16, 1);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      const pixels = new Uint8Array(64);
      gl.readPixels(0, 0, 16, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return points.map((_, i) => Array.from(pixels.subarray(4 * i, 4 * i + 4)));
    };
    /** Whether the table on the GPU holds the CPU copy. */
    const tableOnGpu = () => {
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, textures.table, 0);
      const read = new Uint32Array(4 * range.width * range.height);
      gl.readPixels(0, 0, range.width, range.height, gl.RGBA_INTEGER, gl.UNSIGNED_INT, read);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.deleteFramebuffer(fb);
      for (let k = 0; k < range.width * range.height; k++) {
        if (read[4 * k] !== textures.entries[2 * k] || read[4 * k + 1] !== textures.entries[2 * k + 1]) return false;
      }
      return true;
    };
    /** A page's texels at a mip level. */
    const pageTexels = (page, level) => {
      const size = textures.tileSize >> level;
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, textures.pages, level, page);
      const read = new Uint8Array(4 * size * size);
      gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, read);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.deleteFramebuffer(fb);
      return read;
    };
    const cell = (z, p) => [Math.floor(p[`z${z}`].pixel[0] / 256) * 2 ** (7 - z) - range.x0, Math.floor(p[`z${z}`].pixel[1] / 256) * 2 ** (7 - z) - range.y0];
    const tileAt = (z, p) => [z, Math.floor(p[`z${z}`].pixel[0] / 256), Math.floor(p[`z${z}`].pixel[1] / 256)];
    const entriesAt = (z) => points.map((p) => textures.entry(...cell(7, p))[1]); // zooms shown at each point
    const out = { range: { ...range } };

    out.empty = { colours: sample(4), table: tableOnGpu() };
    // The zoom 4 tiles over the table (x 88..95 of zoom 7: the column of zoom 4 tiles east of
    // 90° E is off it): the base level.
    const base = [];
    for (const [x, y] of [[11, 6], [11, 7], [12, 6]]) {
      textures.put(4, x, y, await bitmap(4, x, y));
      base.push({ z: 4, x, y, key: null, base: true });
    }
    const { tileKey } = await import(`${web}webtiles/tile_key.js`);
    base.forEach((t) => { t.key = tileKey(t.z, t.x, t.y); });
    textures.markWanted(base);
    out.base = { colours: sample(4), zooms: entriesAt(), table: tableOnGpu(), tileSize: textures.tileSize, capacity: textures.capacity,
      offTable: !textures.has(base[2].key), refused: textures.figures.refused };
    base.pop();

    // The zoom 7 tiles of the points, then a zoom 5 tile over one of them: the finer stays.
    const fine = [...new Set(points.map((p) => tileAt(7, p).join('/')))].map((s) => s.split('/').map(Number));
    for (const [z, x, y] of fine) textures.put(z, x, y, await bitmap(z, x, y));
    const khumbu = points.findIndex((p) => p.name === 'Khumbu snow');
    const [, x5, y5] = tileAt(5, { z5: { pixel: points[khumbu].z7.pixel.map((v) => Math.floor(v / 4)) } });
    textures.put(5, x5, y5, await bitmap(5, x5, y5));
    out.fine = { colours: sample(7), zooms: entriesAt(), table: tableOnGpu(), tiles: fine.length };

    // Mipmaps: level 1 of a page is the 2 × 2 mean of level 0.
    const page = textures.resident.get(tileKey(...tileAt(7, points[0])));
    const level0 = pageTexels(page, 0), level1 = pageTexels(page, 1);
    let worst = 0;
    for (let j = 0; j < 128; j++) for (let i = 0; i < 128; i++) for (let c = 0; c < 4; c++) {
      const at = (u, v) => level0[4 * (v * 256 + u) + c];
      const mean = (at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) + at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1)) / 4;
      worst = Math.max(worst, Math.abs(level1[4 * (j * 128 + i) + c] - mean));
    }
    out.mips = { worst };
    let raw = '';
    for (let k = 0; k < level0.length; k += 0x8000) raw += String.fromCharCode(...level0.subarray(k, k + 0x8000));
    out.page = { tile: tileAt(7, points[0]), base64: btoa(raw) };

    // Past the 16 pages: the least recently used go, never the base level (wanted). Zoom 7 tiles
    // away from the points push out the points' tiles and the zoom 5 tile.
    const taken = new Set(fine.map((t) => t.join('/')));
    const others = [];
    for (let y = 49; y <= 56 && others.length < 16; y++) for (let x = 89; x <= 95 && others.length < 16; x++) {
      if (!taken.has(`7/${x}/${y}`)) others.push([7, x, y]);
    }
    const before = textures.figures.evictions;
    for (const [z, x, y] of others) textures.put(z, x, y, await bitmap(z, x, y));
    out.evicted = { colours: sample(4), zooms: entriesAt(), table: tableOnGpu(), evictions: textures.figures.evictions - before,
      baseKept: base.every((t) => textures.has(t.key)), resident: textures.figures.resident };

    // A zoom 5 tile and a zoom 7 tile under it; the zoom 5 one is evicted: its other entries
    // fall back to zoom 4, the zoom 7 tile's entry stays.
    const [z7, x7, y7] = tileAt(7, points[khumbu]);
    textures.put(5, x5, y5, await bitmap(5, x5, y5));
    textures.put(z7, x7, y7, await bitmap(z7, x7, y7));
    // Every tile but the zoom 5 one is wanted: the next page must be its.
    textures.markWanted([...base, ...[...textures.resident.keys()].filter((k) => k !== tileKey(5, x5, y5)).map((key) => ({ key, z: 7, x: 0, y: 0 }))]);
    const square = [];
    for (let j = y5 * 4 - range.y0; j < (y5 + 1) * 4 - range.y0; j++) for (let i = x5 * 4 - range.x0; i < (x5 + 1) * 4 - range.x0; i++) {
      if (i >= 0 && j >= 0 && i < range.width && j < range.height) square.push([i, j]);
    }
    const beforeZooms = square.map(([i, j]) => textures.entry(i, j)[1]);
    textures.put(6, x5 * 2, y5 * 2, await bitmap(6, x5 * 2, y5 * 2));
    out.descendants = {
      fiveGone: !textures.has(tileKey(5, x5, y5)), sixThere: textures.has(tileKey(6, x5 * 2, y5 * 2)),
      beforeZooms, afterZooms: square.map(([i, j]) => textures.entry(i, j)[1]),
      square, khumbuCell: [x7 - range.x0, y7 - range.y0], table: tableOnGpu(),
    };
    out.figures = { ...textures.figures };
    textures.dispose();
    out.errors = gl.getError();
    return out;
  }, { web: `/@fs${projectDir}web/`, tiles: `${viewer.fixturesUrl}webtiles/bmng/`, points: POINTS, image: IMAGE });
  await page.close();

  assert.deepEqual(result.range, { zoom: 7, x0: 89, y0: 49, width: 7, height: 8 }, 'the table: zoom 7 over the image (its east edge, 90° E, is a tile edge)');
  assert.ok(result.empty.colours.every((c) => c.join() === '0,0,0,0') && result.empty.table, 'nothing before the first tile');
  assert.equal(result.base.tileSize, 256);
  assert.equal(result.base.capacity, 16);
  assert.ok(result.base.offTable && result.base.refused === 1, 'a tile off the table is not kept');
  POINTS.forEach((p, i) => {
    assert.ok(near(result.base.colours[i], p.z4.rgba, 1), `${p.name}, zoom 4: ${result.base.colours[i]} vs GDAL ${p.z4.rgba}`);
    assert.ok(near(result.fine.colours[i], p.z7.rgba, 1), `${p.name}, zoom 7: ${result.fine.colours[i]} vs GDAL ${p.z7.rgba}`);
    assert.ok(near(result.evicted.colours[i], p.z4.rgba, 1), `${p.name}, zoom 4 again: ${result.evicted.colours[i]} vs GDAL ${p.z4.rgba}`);
  });
  assert.deepEqual(result.base.zooms, [4, 4, 4, 4, 4]);
  assert.deepEqual(result.fine.zooms, [7, 7, 7, 7, 7], 'the zoom 5 tile put after the zoom 7 ones hides none');
  assert.deepEqual(result.evicted.zooms, [4, 4, 4, 4, 4], 'evicted: back to the base level');
  assert.ok(result.evicted.evictions >= result.fine.tiles + 1 && result.evicted.baseKept && result.evicted.resident === 16,
    JSON.stringify(result.evicted));
  assert.ok(result.base.table && result.fine.table && result.evicted.table && result.descendants.table, 'the GPU table is the CPU copy');
  const d = result.descendants;
  assert.ok(d.fiveGone && d.sixThere, JSON.stringify(d));
  d.square.forEach(([i, j], k) => {
    const khumbu = i === d.khumbuCell[0] && j === d.khumbuCell[1];
    assert.equal(d.beforeZooms[k], khumbu ? 7 : 5);
    // The new zoom 6 tile covers a quarter of the square; elsewhere zoom 4 again; the zoom 7 tile stays.
    const inSix = i < d.square[0][0] + 2 && j < d.square[0][1] + 2;
    assert.equal(d.afterZooms[k], khumbu ? 7 : inSix ? 6 : 4, `cell ${i}, ${j}`);
  });
  assert.ok(result.mips.worst <= 1, `mip level 1 within 1 of the 2 × 2 means (${result.mips.worst})`);
  const [z, x, y] = result.page.tile;
  const png = decode(readFileSync(`${FIXTURES}bmng/${z}/${x}/${y}.png`));
  assert.equal(png.channels, 4);
  assert.deepEqual(Buffer.from(result.page.base64, 'base64'), Buffer.from(png.data), 'the page holds the decoded tile, row 0 its north edge');
  assert.equal(result.errors, 0, 'no GL error');
});

/** Ground metres of the image's extent as the page makes them from degrees, and the map to Web Mercator. */
const EXTENT_X = (IMAGE.east - IMAGE.west) * 111320 * Math.cos(((IMAGE.north + IMAGE.south) / 2) * Math.PI / 180);
const EXTENT_Z = (IMAGE.north - IMAGE.south) * 110574;

/** The camera over the Khumbu, looking north-west from 120 km, as gl-matrix builds it. */
function camera(height, shift = 0) {
  const eye = [EXTENT_X * 0.8 + shift, 120000, EXTENT_Z * 0.6], target = [EXTENT_X * 0.7 + shift, 0, EXTENT_Z * 0.5];
  const fovY = (50 * Math.PI) / 180;
  const viewProjection = mat4.multiply(mat4.create(), mat4.perspective(mat4.create(), fovY, 1.5, 100, 4e6),
    mat4.lookAt(mat4.create(), eye, target, [0, 1, 0]));
  return { position: eye, viewProjection: Array.from(viewProjection), fovY, height };
}

/** Opens a WebTileLayer in the page on `template`, updates it for the camera and waits until nothing is in flight. */
async function runLayer(page, template, cam) {
  return page.evaluate(async ({ web, template, cam, extentX, extentZ, image }) => {
    const { WebTileLayer } = await import(`${web}webtiles/web_tile_layer.js`);
    const { lonLatToWorld } = await import(`${web}webtiles/web_mercator.js`);
    const canvas = document.createElement('canvas');
    const gl = canvas.getContext('webgl2');
    const scratch = [0, 0];
    const toMercator = (x, z) => lonLatToWorld(image.west + (x / extentX) * (image.east - image.west),
      image.north - (z / extentZ) * (image.north - image.south), scratch);
    const messages = [];
    let changes = 0;
    const layer = new WebTileLayer(gl, template, { toMercator, terrain: { extentX, extentZ, low: 0, high: 17504 },
      onChange: () => { changes++; }, onMessage: (message, fault) => messages.push({ message, kind: fault.kind }) });
    const camera = { position: cam.position, viewProjection: new Float32Array(cam.viewProjection), fovY: cam.fovY };
    const chose = layer.update(camera, { height: cam.height });
    const again = layer.update(camera, { height: cam.height });
    const settled = async () => {
      for (let i = 0; i < 4000; i++) {
        // Done: nothing in flight, and no retry waiting unless a fault was told.
        if (layer.requests.pending === 0 && (layer.requests.timer === null || messages.length > 0)) return;
        await new Promise((resolve) => setTimeout(resolve, 5));
      }
    };
    await settled();
    const figures = layer.figures;
    const table = layer.table;
    let empty = 0;
    for (let j = 0; j < table.height; j++) for (let i = 0; i < table.width; i++) if (layer.textures.entry(i, j)[0] === 0) empty++;
    const result = { chose, again, figures, messages, changes, table: { ...table }, empty, attribution: layer.attribution,
      wanted: layer.wanted.map((t) => `${t.z}/${t.x}/${t.y}`), base: layer.wanted.filter((t) => t.base).length,
      baseZoom: layer.selection.baseZoom };
    layer.dispose();
    return result;
  }, { web: `/@fs${projectDir}web/`, template, cam, extentX: EXTENT_X, extentZ: EXTENT_Z, image: IMAGE });
}

test('a tile layer fetches the base level and the view\'s tiles from a tile server on another origin', async () => {
  const page = await modulePage();
  server.reset();
  const result = await runLayer(page, `${server.url}/{z}/{x}/{y}.png|zoom=3-7|attribution=NASA Earth Observatory`, camera(400));
  await page.close();
  assert.equal(result.chose, true);
  assert.equal(result.again, false, 'the same view again: no new selection');
  assert.deepEqual(result.messages, []);
  assert.equal(result.attribution, 'NASA Earth Observatory');
  assert.deepEqual(result.table, { zoom: 7, x0: 89, y0: 49, width: 7, height: 8 });
  assert.equal(result.baseZoom, 5);
  assert.equal(result.base, 6, 'the base level: 2 × 3 tiles of zoom 5');
  const requested = server.tilesRequested();
  assert.deepEqual([...requested].sort(), [...result.wanted].sort(), 'every wanted tile fetched, once, and nothing else');
  assert.ok(result.wanted.slice(0, 6).every((t) => t.startsWith('5/')), 'the base level first');
  assert.ok(result.wanted.some((t) => t.startsWith('7/')), 'and zoom 7 near the camera');
  assert.equal(result.figures.fetched, requested.length);
  assert.equal(result.figures.resident, requested.length);
  assert.equal(result.figures.bytesFetched, requested.reduce((sum, t) => sum + readFileSync(`${FIXTURES}bmng/${t}.png`).length, 0));
  assert.equal(result.empty, 0, 'every entry of the table has a tile');
  assert.ok(result.changes >= requested.length, 'each tile asked for a frame');
});

test('a server that refuses cross-origin reads, one that is down and one without the tiles: one message each', async () => {
  const page = await modulePage();
  const template = `${server.url}/{z}/{x}/{y}.png|zoom=3-7`;
  const told = {};
  try {
    for (const fault of ['no-cors', 'down', 'missing', 'not-image']) {
      await server.setFault(fault);
      told[fault] = await runLayer(page, template, camera(400));
    }
  } finally {
    await server.setFault(null);
    await page.close();
  }
  const host = server.url.replace('http://', '');
  assert.deepEqual(told['no-cors'].messages.map((m) => m.kind), ['cors']);
  assert.match(told['no-cors'].messages[0].message, new RegExp(`^the tile server ${host} answers but does not let this page read its tiles`));
  assert.deepEqual(told.down.messages.map((m) => m.kind), ['unreachable']);
  assert.match(told.down.messages[0].message, new RegExp(`^cannot reach the tile server ${host} \\(it is down, or the address is wrong\\)`));
  assert.deepEqual(told.missing.messages.map((m) => m.kind), ['http']);
  assert.match(told.missing.messages[0].message, new RegExp(`^HTTP 404 for http://${host}/5/\\d+/\\d+\\.png$`));
  assert.deepEqual(told['not-image'].messages.map((m) => m.kind), ['not-image']);
  for (const fault of Object.keys(told)) assert.equal(told[fault].figures.resident, 0, `${fault}: nothing drawn`);
  assert.ok(told.missing.figures.failed > 1, 'many tiles failed, one message');
});

test('a layer chooses again at most every 100 ms, and stands in the zoom above for a zoom the service lacks', async () => {
  const page = await modulePage();
  server.reset();
  server.options.missingZooms = [7];
  let result;
  try {
    result = await page.evaluate(async ({ web, template, cams, extentX, extentZ, image }) => {
      const { WebTileLayer } = await import(`${web}webtiles/web_tile_layer.js`);
      const { lonLatToWorld } = await import(`${web}webtiles/web_mercator.js`);
      const gl = document.createElement('canvas').getContext('webgl2');
      const scratch = [0, 0];
      const toMercator = (x, z) => lonLatToWorld(image.west + (x / extentX) * (image.east - image.west),
        image.north - (z / extentZ) * (image.north - image.south), scratch);
      const messages = [];
      let asked = 0;
      const layer = new WebTileLayer(gl, template, { toMercator, terrain: { extentX, extentZ, low: 0, high: 17504 },
        onChange: () => { asked++; }, onMessage: (message) => messages.push(message) });
      const [first, second, third] = cams.map((c) => ({ position: c.position, viewProjection: new Float32Array(c.viewProjection), fovY: c.fovY }));
      const idle = async () => {
        while (layer.requests.pending > 0) await new Promise((resolve) => setTimeout(resolve, 5));
      };
      const out = { first: layer.update(first, { height: 400 }) };
      const askedBefore = asked;
      // Moved at once: too soon to choose again, and a frame is asked for when it is time.
      out.tooSoon = layer.update(second, { height: 400 });
      out.timerSet = layer.timer !== null;
      const waitStart = performance.now();
      while (layer.timer !== null) await new Promise((resolve) => setTimeout(resolve, 2));
      out.waitedMs = performance.now() - waitStart;
      out.askedByTimer = asked > askedBefore;
      await idle();
      out.second = layer.update(second, { height: 400 });
      await idle();
      const zoom7 = { ...layer.figures };
      // Once zoom 7 failed, the next view wants the zoom 6 tiles above them instead.
      await new Promise((resolve) => setTimeout(resolve, 120));
      out.third = layer.update(third, { height: 400 });
      await idle();
      out.wanted = layer.wanted.map((t) => `${t.z}/${t.x}/${t.y}`);
      out.residentZooms = [...layer.textures.resident.keys()].map((k) => layer.textures.tileZ[layer.textures.resident.get(k)]);
      out.figures = { before: zoom7, after: { ...layer.figures } };
      out.messages = messages;
      layer.dispose();
      return out;
    }, { web: `/@fs${projectDir}web/`, template: `${server.url}/{z}/{x}/{y}.png|zoom=3-7`,
      cams: [camera(400), camera(400, 1000), camera(400, 2000)],
      extentX: EXTENT_X, extentZ: EXTENT_Z, image: IMAGE });
  } finally {
    server.options.missingZooms = [];
    await page.close();
  }
  assert.deepEqual([result.first, result.tooSoon, result.second, result.third], [true, false, true, true]);
  assert.ok(result.timerSet && result.askedByTimer && result.waitedMs < 1000, `a frame asked for after ${result.waitedMs.toFixed(0)} ms`);
  assert.equal(result.messages.length, 1);
  assert.match(result.messages[0], /^HTTP 404 for http:\/\/127\.0\.0\.1:\d+\/7\//);
  assert.ok(!result.wanted.some((t) => t.startsWith('7/')), 'no zoom 7 tile wanted once they failed');
  assert.ok(result.wanted.some((t) => t.startsWith('6/')), 'their zoom 6 parents instead');
  const requested = server.tilesRequested();
  assert.equal(requested.filter((t) => t.startsWith('7/')).length, new Set(requested.filter((t) => t.startsWith('7/'))).size,
    'no zoom 7 tile asked for twice');
  assert.ok(result.residentZooms.every((z) => z <= 6) && result.residentZooms.includes(6));
});

test('after a lost context the pages and the table are made again from the tiles put anew', async () => {
  const page = await modulePage();
  const result = await page.evaluate(async ({ web, tiles }) => {
    const { WebTileTextures } = await import(`${web}render/shading/web_tile_textures.js`);
    const canvas = document.createElement('canvas');
    const gl = canvas.getContext('webgl2');
    const lose = gl.getExtension('WEBGL_lose_context');
    const timeout = (what) => new Promise((_, reject) => setTimeout(() => reject(new Error(`no ${what} event within 30 s`)), 30000));
    const bitmap = async (z, x, y) => createImageBitmap(await (await fetch(`${tiles}${z}/${x}/${y}.png`)).blob(),
      { premultiplyAlpha: 'none', colorSpaceConversion: 'default' });
    const textures = new WebTileTextures(gl, { memoryBytes: 1 });
    textures.setRange({ zoom: 7, x0: 89, y0: 49, width: 7, height: 8 });
    const readPage = (page) => {
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, textures.pages, 0, page);
      const read = new Uint8Array(4 * 256 * 256);
      gl.readPixels(0, 0, 256, 256, gl.RGBA, gl.UNSIGNED_BYTE, read);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return read;
    };
    const readTable = () => {
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, textures.table, 0);
      const read = new Uint32Array(4 * 7 * 8);
      gl.readPixels(0, 0, 7, 8, gl.RGBA_INTEGER, gl.UNSIGNED_INT, read);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return Array.from(read.filter((_, k) => k % 4 < 2));
    };
    const tile = await bitmap(6, 46, 26);
    textures.put(6, 46, 26, tile);
    const before = { page: readPage(textures.resident.get([...textures.resident.keys()][0])), table: readTable() };
    const lost = new Promise((resolve) => canvas.addEventListener('webglcontextlost', (e) => { e.preventDefault(); resolve(); }, { once: true }));
    lose.loseContext();
    await Promise.race([lost, timeout('webglcontextlost')]);
    const keptWhileLost = textures.put(6, 46, 26, tile);
    const restored = new Promise((resolve) => canvas.addEventListener('webglcontextrestored', resolve, { once: true }));
    await new Promise((resolve) => setTimeout(resolve, 0)); // a restore asked for in the task that handled the loss never comes
    lose.restoreContext();
    await Promise.race([restored, timeout('webglcontextrestored')]);
    textures.forgetGl();
    const emptied = { resident: textures.figures.resident, entries: Array.from(textures.entries).some((v) => v !== 0) };
    textures.put(6, 46, 26, tile);
    textures.bind(0, 1);
    const after = { page: readPage(textures.resident.get([...textures.resident.keys()][0])), table: readTable() };
    const same = before.page.length === after.page.length && before.page.every((v, i) => v === after.page[i]);
    return { keptWhileLost, emptied, same, tableBefore: before.table, tableAfter: after.table, cpu: Array.from(textures.entries),
      error: gl.getError() };
  }, { web: `/@fs${projectDir}web/`, tiles: `${viewer.fixturesUrl}webtiles/bmng/` });
  await page.close();
  assert.equal(result.keptWhileLost, false, 'nothing is kept while the context is lost');
  assert.deepEqual(result.emptied, { resident: 0, entries: false }, 'forgetGl empties the table and the pages');
  assert.ok(result.same, 'the page holds the same texels again');
  assert.deepEqual(result.tableAfter, result.tableBefore);
  assert.deepEqual(result.tableAfter, result.cpu);
  assert.equal(result.tableAfter.filter((v, k) => k % 2 === 1 && v === 6).length, 4, 'the zoom 6 tile over 2 x 2 entries');
  assert.equal(result.error, 0);
});
