// Debian's Chromium through playwright-core, as `hexlod regress` and the browser tests run it
// (never a browser that a tool downloads), and a free localhost port for the page's server.
import { existsSync, statSync } from 'node:fs';
import { createServer as createNetServer } from 'node:net';

export const DEFAULT_CHROMIUM = '/usr/bin/chromium';

/** The machine, not the input, failed: no browser, or one that does not start or dies. */
export class EnvironmentError extends Error {}
const CHROMIUM_FLAGS = [
  '--no-sandbox', // CI runs as root
  '--disable-gpu', '--enable-unsafe-swiftshader', // WebGL2 on the CPU: the same pixels on every run
  '--disable-quic', '--no-first-run', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', // the machine has no network but the registries
];

/** A free TCP port on localhost (Vite takes port 0 as "the default port"). */
export async function freePort() {
  const probe = createNetServer();
  await new Promise((resolve) => probe.listen(0, '127.0.0.1', resolve));
  const { port } = probe.address();
  await new Promise((resolve) => probe.close(resolve));
  return port;
}

/**
 * Starts headless Chromium (CHROMIUM_PATH or /usr/bin/chromium unless `path` is given), with
 * `extraArgs` after the usual flags. Throws one-line errors when it is missing or does not start.
 */
export async function launchChromium(path = process.env.CHROMIUM_PATH || DEFAULT_CHROMIUM, extraArgs = []) {
  if (!existsSync(path) || !statSync(path).isFile()) {
    throw new EnvironmentError(`no Chromium at ${path}: install Debian's (apt-get install chromium) or give --chromium PATH`);
  }
  const { chromium } = await import('playwright-core');
  try {
    return await chromium.launch({ executablePath: path, headless: true, args: [...CHROMIUM_FLAGS, ...extraArgs] });
  } catch (error) {
    // Playwright's own words for a program that exits at once ("Target page, context or browser
    // has been closed") do not say that the program is not a working Chromium.
    const why = String(error.message).split('\n')[0].replace(/^browserType\.launch: /, '');
    const closed = /has been closed|exited|Browser closed/i.test(why);
    throw new EnvironmentError(`Chromium at ${path} did not start${closed ? ': the program exited at once; is it a Chromium browser?' : `: ${why}`}`);
  }
}
