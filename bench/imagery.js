#!/usr/bin/env node
// Draping an 8192 x 8192 JPEG on the default terrain, in the page (headless Chromium, WebGL on
// SwiftShader). Prints:
//   1. drop to the first frame drawn with the image, RUNS times (median and each), split into
//      before the decode (reading the header, placing, planning the tiling), the decode
//      (createImageBitmap), the upload with its mipmaps, and the first frame (waiting for it and drawing it);
//   2. GPU bytes per image pixel (the page's own gpuBytes) under this GPU's MAX_TEXTURE_SIZE and
//      with tiles forced to 2048 texels (?imagetile=2048);
//   3. frame time with and without the image, the same fixed oblique view, in blocks that
//      alternate with the drops of 1 so that both see the same load; the ratio is the figure.
// The JPEG is made in the page at run time (gradients, texture and grain, so that it compresses
// like a photo rather than like a flat colour) and dropped there as a File in a DataTransfer,
// as a person's drop arrives: carrying 20 MB through page.evaluate as text would time the harness.
// The split is timed from outside the product: the benchmark wraps createImageBitmap and
// generateMipmap in the page (after the mipmaps it reads a pixel, so that the upload's time
// includes the GPU's work rather than only its submission). The page waits for the GPU after
// drawing (?timing=1), so frame times include SwiftShader's rasterisation.
// Usage: node bench/imagery.js [--viewport 640x360] [--runs 3] [--frames 20] [--size 8192]
import { parseArgs } from 'node:util';
import { startViewer } from '../lib/page_harness.js';
import { drawBlock, obliqueTimedPage } from '../lib/page_frames.js';

const { values } = parseArgs({ options: { viewport: { type: 'string' }, runs: { type: 'string' }, frames: { type: 'string' },
  size: { type: 'string' } } });
const [width, height] = (values.viewport ?? '640x360').split('x').map(Number);
const RUNS = Number(values.runs ?? 3);
const FRAMES = Number(values.frames ?? 20);
const SIZE = Number(values.size ?? 8192);
const NAME = `bench_${SIZE}.jpg`;
const SETTLE_FRAMES = 2;
const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1];
const ms = (v) => `${Math.round(v).toLocaleString('en')} ms`;

/**
 * Makes the JPEG in the page (window.benchJpeg, a Blob) and installs the probe that times a drop
 * (window.benchProbe). Returns the JPEG's size in bytes and the page's MAX_TEXTURE_SIZE.
 */
function prepare(page) {
  return page.evaluate(async (size) => {
    // Smooth structure at two scales (fields, hills) from separable tables, and a grain from a
    // fixed-seed generator: the same picture on every run.
    const wave = (n, f, phase) => Float32Array.from({ length: n }, (_, i) => Math.sin(i * f + phase));
    const [ax, ay, bx, by, cx, cy] = [wave(size, 0.0021, 0), wave(size, 0.0017, 1), wave(size, 0.023, 2),
      wave(size, 0.029, 3), wave(size, 0.11, 4), wave(size, 0.13, 5)];
    const canvas = new OffscreenCanvas(size, size);
    const context = canvas.getContext('2d');
    const band = 256;
    const rows = context.createImageData(size, band);
    const d = rows.data;
    let seed = 12345;
    for (let y0 = 0; y0 < size; y0 += band) {
      for (let y = 0; y < band; y++) {
        const Y = y0 + y;
        for (let x = 0, k = y * size * 4; x < size; x++, k += 4) {
          seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0;
          const grain = ((seed >>> 24) - 128) / 5;
          const large = 70 * ax[x] * ay[Y], middle = 25 * bx[x] * by[Y], small = 10 * cx[x] * cy[Y];
          d[k] = 120 + large + middle + small + grain;
          d[k + 1] = 110 + 0.8 * large - middle + small + grain + 30 * (Y / size);
          d[k + 2] = 90 - 0.5 * large + 0.5 * middle - small + grain + 40 * (x / size);
          d[k + 3] = 255;
        }
      }
      context.putImageData(rows, 0, y0);
    }
    window.benchJpeg = await canvas.convertToBlob({ type: 'image/jpeg', quality: 0.85 });

    // The probe: armed for one drop; the times are performance.now() of each step's end.
    const probe = window.benchProbe = { armed: false, drop: 0, decodeStart: 0, decodeEnd: 0, uploadEnd: 0, frameEnd: 0 };
    const createBitmap = window.createImageBitmap;
    window.createImageBitmap = function (source, ...rest) {
      const decoding = createBitmap.call(this, source, ...rest);
      if (!probe.armed || !(source instanceof Blob)) return decoding; // the overview's resize is upload work
      probe.decodeStart = performance.now();
      return decoding.then((bitmap) => { probe.decodeEnd = performance.now(); return bitmap; });
    };
    const generateMipmap = WebGL2RenderingContext.prototype.generateMipmap;
    const pixel = new Uint8Array(4);
    WebGL2RenderingContext.prototype.generateMipmap = function (target) {
      generateMipmap.call(this, target);
      if (!probe.armed) return;
      // A pixel read waits until the GPU has done every command before it: the uploads and this
      // mip chain (the commands are only queued when texSubImage and generateMipmap return).
      if (this.checkFramebufferStatus(this.FRAMEBUFFER) === this.FRAMEBUFFER_COMPLETE) {
        this.readPixels(0, 0, 1, 1, this.RGBA, this.UNSIGNED_BYTE, pixel);
      }
      probe.uploadEnd = performance.now();
    };
    // The end of the first frame drawn with the image: the page counts frames as each ends.
    const h = window.hexlod;
    let frames = h.frames;
    Object.defineProperty(h, 'frames', { enumerable: true, configurable: true, get: () => frames, set: (n) => {
      frames = n;
      if (probe.armed && h.image && !probe.frameEnd) probe.frameEnd = performance.now();
    } });
    const gl = document.createElement('canvas').getContext('webgl2');
    return { bytes: window.benchJpeg.size, maxTextureSize: gl.getParameter(gl.MAX_TEXTURE_SIZE) };
  }, SIZE);
}

/** Drops the JPEG on the page as a person does and times it to the first frame drawn with it. */
function timedDrop(page, name) {
  return page.evaluate((n) => new Promise((resolve, reject) => {
    const probe = window.benchProbe, h = window.hexlod;
    Object.assign(probe, { armed: true, decodeStart: 0, decodeEnd: 0, uploadEnd: 0, frameEnd: 0 });
    const transfer = new DataTransfer();
    transfer.items.add(new File([window.benchJpeg], n, { type: 'image/jpeg' }));
    probe.drop = performance.now();
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
    const wait = () => {
      if (probe.frameEnd) {
        probe.armed = false;
        resolve({ ...probe, image: h.image });
      } else if (h.error || document.getElementById('status').classList.contains('error')) {
        probe.armed = false;
        reject(new Error(`the drop failed: ${document.getElementById('status').textContent}`));
      } else setTimeout(wait, 20);
    };
    wait();
  }), name);
}

const viewer = await startViewer();
try {
  // 1 and 3: the real MAX_TEXTURE_SIZE.
  const { page, problems, view } = await obliqueTimedPage(viewer, '', { width, height });
  const made = Date.now();
  const { bytes, maxTextureSize } = await prepare(page);
  console.log(`JPEG ${SIZE} × ${SIZE}, quality 0.85: ${(bytes / 2 ** 20).toFixed(1)} MB (${(8 * bytes / SIZE ** 2).toFixed(2)} bits a pixel), ` +
    `made in the page in ${ms(Date.now() - made)}; MAX_TEXTURE_SIZE ${maxTextureSize}`);
  console.log(view);

  const drops = [], withImage = [], withoutImage = [];
  // Blocks without, with, without, ... the image: each drop of 1 starts a block with it, and
  // removing the image a block without. The first frames of a block are left out: they may pay
  // for what the drop or the removal left behind (freed textures, the decoded bitmap's garbage).
  const block = async () => (await drawBlock(page, FRAMES + SETTLE_FRAMES)).slice(SETTLE_FRAMES);
  withoutImage.push(await block());
  for (let run = 0; run < RUNS; run++) {
    drops.push(await timedDrop(page, NAME));
    withImage.push(await block());
    if (run === RUNS - 1) break;
    await page.evaluate(() => window.hexlod.images.remove());
    withoutImage.push(await block());
  }
  const image = drops[0].image;
  const parts = drops.map((p) => ({ total: p.frameEnd - p.drop, before: p.decodeStart - p.drop, decode: p.decodeEnd - p.decodeStart,
    upload: p.uploadEnd - p.decodeEnd, frame: p.frameEnd - p.uploadEnd }));
  const line = (key) => `median ${ms(median(parts.map((p) => p[key])))} (${parts.map((p) => ms(p[key])).join(', ')})`;
  console.log(`\n1. Drop to the first frame drawn with the image (${image.width} × ${image.height}, ${image.how}), ${RUNS} runs:`);
  console.log(`  drop → first draped frame     ${line('total')}`);
  console.log(`    before the decode           ${line('before')}`);
  console.log(`    decode (createImageBitmap)  ${line('decode')}`);
  console.log(`    upload + mipmaps (GPU done) ${line('upload')}`);
  console.log(`    first frame (wait + draw)   ${line('frame')}`);

  // 3 (measured above, printed after 2): the page's own figures of each frame.
  const cpu = (blocks) => median(blocks.flat().map((f) => f.cpuMs)), draw = (blocks) => median(blocks.flat().map((f) => f.drawMs));
  const perBlock = (blocks) => blocks.map((b) => Math.round(cpu([b]))).join(', ');

  // 2: gpuBytes under this GPU's limit, then with tiles forced (a page of its own).
  console.log(`\n2. GPU bytes per image pixel (the page's gpuBytes: RGBA8 texels of tiles with their aprons, and the overview, × 4/3 for mipmaps):`);
  console.log(`  MAX_TEXTURE_SIZE ${maxTextureSize}: ${(image.gpuBytes / 2 ** 20).toFixed(1)} MiB, ${(image.gpuBytes / (image.width * image.height)).toFixed(3)} B a pixel`);
  if (problems.length) throw new Error(problems.join('\n'));
  await page.close();
  const tiled = await obliqueTimedPage(viewer, '&imagetile=2048', { width, height });
  await prepare(tiled.page);
  const drop = await timedDrop(tiled.page, NAME);
  const t = drop.image;
  console.log(`  ?imagetile=2048: ${(t.gpuBytes / 2 ** 20).toFixed(1)} MiB, ${(t.gpuBytes / (t.width * t.height)).toFixed(3)} B a pixel ` +
    `(drop → first draped frame ${ms(drop.frameEnd - drop.drop)}: decode ${ms(drop.decodeEnd - drop.decodeStart)}, ` +
    `upload + mipmaps + overview ${ms(drop.uploadEnd - drop.decodeEnd)}, one run)`);
  if (tiled.problems.length) throw new Error(tiled.problems.join('\n'));
  await tiled.page.close();

  console.log(`\n3. Frame time, the same view, ${FRAMES} frames a block, blocks alternating with the drops ` +
    `(the first ${SETTLE_FRAMES} of each left out; ${withImage.flat().length} frames with the image, ${withoutImage.flat().length} without):`);
  console.log(`  whole frame (GPU included)  with ${ms(cpu(withImage))}, without ${ms(cpu(withoutImage))}, ratio ${(cpu(withImage) / cpu(withoutImage)).toFixed(2)}`);
  console.log(`  draw until done             with ${ms(draw(withImage))}, without ${ms(draw(withoutImage))}, ratio ${(draw(withImage) / draw(withoutImage)).toFixed(2)}`);
  console.log(`  whole frame, median of each block in order: without ${perBlock(withoutImage)} ms; with ${perBlock(withImage)} ms`);
} finally {
  await viewer.close();
}
