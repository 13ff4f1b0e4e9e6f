// Chromium through playwright-core, as `hexlod regress` and the browser tests run it, and a free
// localhost port for the page's server. The browser is one already on the machine, never one
// that this code downloads: the one named (--chromium, CHROMIUM_PATH), else Debian's, else one
// that `npx playwright-core install chromium` (or Playwright's own installer) put in its cache.
import { existsSync, readdirSync, statSync } from 'node:fs';
import { createServer as createNetServer } from 'node:net';
import { homedir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const DEFAULT_CHROMIUM = '/usr/bin/chromium';
/** How to get a browser, in the one line of a machine without one. */
export const INSTALL_CHROMIUM = 'apt-get install chromium (Debian) or npx playwright-core install chromium';

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

const isFile = (path) => existsSync(path) && statSync(path).isFile();

/**
 * The folder of Playwright's downloaded browsers, as playwright-core computes it:
 * PLAYWRIGHT_BROWSERS_PATH ("0": inside the playwright-core package), else the user's cache.
 */
export function playwrightBrowsersDir(env = process.env, home = homedir()) {
  const given = env.PLAYWRIGHT_BROWSERS_PATH;
  if (given === '0') {
    try {
      return join(fileURLToPath(new URL('.', import.meta.resolve('playwright-core/package.json'))), '.local-browsers');
    } catch {
      return null;
    }
  }
  if (given) return given;
  return join(env.XDG_CACHE_HOME || join(home, '.cache'), 'ms-playwright');
}

// Inside a browser folder of Playwright (chromium-REVISION, chromium_headless_shell-REVISION):
// Chrome for Testing's layout of recent versions, then the older Chromium builds' layout.
const PLAYWRIGHT_LAYOUTS = [
  ['chromium-', ['chrome-linux64/chrome', 'chrome-linux/chrome']],
  ['chromium_headless_shell-', ['chrome-headless-shell-linux64/chrome-headless-shell', 'chrome-linux/headless_shell']],
];

/** Playwright's Chromium programs in `dir`: full Chromium before the headless shell, newest revision first. */
export function playwrightChromiums(dir) {
  if (!dir || !existsSync(dir)) return [];
  const names = readdirSync(dir);
  const found = [];
  for (const [prefix, programs] of PLAYWRIGHT_LAYOUTS) {
    const revisions = names.filter((name) => name.startsWith(prefix) && /^\d+$/.test(name.slice(prefix.length)))
      .sort((a, b) => Number(b.slice(prefix.length)) - Number(a.slice(prefix.length)));
    for (const name of revisions) {
      for (const program of programs) if (isFile(join(dir, name, program))) found.push(join(dir, name, program));
    }
  }
  return found;
}

/**
 * The Chromium to run: `given` (--chromium) or CHROMIUM_PATH when set (and then only it), else
 * Debian's /usr/bin/chromium, else Playwright's newest. Throws EnvironmentError with one line
 * saying how to get one.
 * @param {{ given?: string, env?: object, home?: string, system?: string }} [where] for tests: the
 *   environment, home folder and system path to look at instead of the machine's
 */
export function findChromium({ given, env = process.env, home = homedir(), system = DEFAULT_CHROMIUM } = {}) {
  const named = given ?? env.CHROMIUM_PATH;
  if (named) {
    if (isFile(named)) return named;
    throw new EnvironmentError(`no Chromium at ${named} (${given ? '--chromium' : 'CHROMIUM_PATH'}): name the Chromium program, or install one with ${INSTALL_CHROMIUM}`);
  }
  if (isFile(system)) return system;
  const dir = playwrightBrowsersDir(env, home);
  const [newest] = playwrightChromiums(dir);
  if (newest) return newest;
  throw new EnvironmentError(`no Chromium found (not at ${system}, none of Playwright's in ${dir ?? 'playwright-core/.local-browsers'}): install one with ${INSTALL_CHROMIUM}, or give --chromium PATH`);
}

/**
 * Starts headless Chromium (findChromium() unless `path` is given), with `extraArgs` after the
 * usual flags. Throws one-line errors when it is missing or does not start.
 */
export async function launchChromium(path = undefined, extraArgs = []) {
  path = findChromium({ given: path });
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
