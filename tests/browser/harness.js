// Shared set-up of the browser tests: a Vite server on a free localhost port and Debian's
// Chromium driven by playwright-core (never a browser that a tool downloads).
import { createServer } from 'vite';
import { chromium } from 'playwright-core';
import { decode } from 'fast-png';
import { mkdirSync } from 'node:fs';
import { createServer as createNetServer } from 'node:net';
import { fileURLToPath } from 'node:url';

export const projectDir = fileURLToPath(new URL('../..', import.meta.url));
export const outDir = `${projectDir}tests/out`;

const CHROMIUM_FLAGS = [
  '--no-sandbox', // CI runs as root
  '--disable-gpu', '--enable-unsafe-swiftshader', // WebGL2 on the CPU: no GPU here
  '--disable-quic', '--no-first-run', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', // the machine has no network but the registries
];

/** A free TCP port on localhost (Vite treats port 0 as "use the default"). */
async function freePort() {
  const probe = createNetServer();
  await new Promise((resolve) => probe.listen(0, '127.0.0.1', resolve));
  const { port } = probe.address();
  await new Promise((resolve) => probe.close(resolve));
  return port;
}

/** Starts the dev server and the browser; returns { url, browser, close() }. */
export async function startViewer() {
  const server = await createServer({
    configFile: `${projectDir}vite.config.js`,
    root: `${projectDir}public`,
    server: { port: await freePort(), strictPort: true, host: '127.0.0.1' },
    logLevel: 'error',
  });
  await server.listen();
  const { port } = server.httpServer.address();
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_FLAGS,
  });
  mkdirSync(outDir, { recursive: true });
  return {
    url: `http://127.0.0.1:${port}/`,
    browser,
    async close() {
      await browser.close();
      await server.close();
    },
  };
}

/** Opens a page that records console errors, page errors and failed requests in `problems`. */
export async function openPage(browser, url, viewport = { width: 960, height: 600 }) {
  const page = await browser.newPage({ viewport });
  const problems = [];
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console.error: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));
  await page.goto(url);
  return { page, problems };
}

/** The renderer's clear colour (web/renderer.js SKY_COLOR) as 8-bit RGB. */
const SKY_RGB = [158, 189, 224];

/**
 * Colour statistics of a PNG screenshot: distinct quantised colours, luminance spread, and the
 * fractions of pixels that are the sky (clear) colour, snow white, and warm ground or rock.
 */
export function pixelStats(png) {
  const image = decode(png);
  const { data, channels } = image;
  const colours = new Set();
  let sum = 0, sumSq = 0, n = 0, sky = 0, snow = 0, ground = 0;
  for (let k = 0; k < data.length; k += channels * 7) {
    const r = data[k], g = data[k + 1], b = data[k + 2];
    colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
    if (Math.abs(r - SKY_RGB[0]) + Math.abs(g - SKY_RGB[1]) + Math.abs(b - SKY_RGB[2]) < 12) sky += 1;
    else if (r > 215 && g > 215 && b > 215) snow += 1;        // lit snow of the high peaks
    else if (r >= g && g >= b && r - b > 12) ground += 1;      // warm rock and dry ground
    const y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    sum += y; sumSq += y * y; n += 1;
  }
  const mean = sum / n;
  return { colours: colours.size, luminanceStd: Math.sqrt(sumSq / n - mean * mean), skyFraction: sky / n,
    snowFraction: snow / n, groundFraction: ground / n };
}

/**
 * The fraction of a PNG screenshot that is sky drawn by the scattering model (issue 14): in each
 * column, the run of blue pixels (blue above red and green) from the top edge down to the first
 * pixel that is not. Blue-grey shadows and haze on the terrain below do not count.
 */
export function skyFromTop(png) {
  const { width, height, data, channels } = decode(png);
  let sky = 0;
  for (let x = 0; x < width; ++x) {
    for (let y = 0; y < height; ++y) {
      const k = (y * width + x) * channels;
      if (!(data[k + 2] > data[k] + 10 && data[k + 2] >= data[k + 1])) break;
      sky += 1;
    }
  }
  return sky / (width * height);
}
