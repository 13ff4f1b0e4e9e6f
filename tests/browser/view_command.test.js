// `./hexlod.sh view` as a person runs it in a fresh clone: it builds only the page's
// WebAssembly module, and what it serves draws the default terrain. Runs in a copy of the
// repository's files with no build/ or dist/, so a file the page needs and the reduced build
// misses fails here.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { copyFileSync, existsSync, lstatSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync,
  statSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { freePort, launchChromium } from '../../lib/chromium.js';
import { openPage, outDir, pixelStats, pageReady, projectDir } from '../../lib/page_harness.js';

let tree; // the copy of the repository
const servers = new Set(); // `view` processes still running, stopped in after() if a test failed

/**
 * The work tree's files as they are now: the tracked ones and the new ones not yet added (a
 * change in progress may import a new file), not the ignored ones, so no build/, dist/ or
 * node_modules. node_modules comes as a folder of links to the repository's packages: only the
 * links live in the copy, so removing the copy (or an `npm ci` in it) unlinks them and never
 * reaches the real packages. Vite's caches (.vite, .vite-temp) are left out: the copy's server
 * keeps its own.
 */
function copyRepository() {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-view-'));
  const files = execFileSync('git', ['ls-files', '-z', '--cached', '--others', '--exclude-standard'],
    { cwd: projectDir, encoding: 'utf8' }).split('\0');
  for (const file of files) {
    if (!file || /^(build|dist|node_modules)(\/|$)/.test(file) || !existsSync(join(projectDir, file))) continue;
    mkdirSync(dirname(join(dir, file)), { recursive: true });
    copyFileSync(join(projectDir, file), join(dir, file)); // keeps the mode: hexlod.sh stays executable
  }
  const packages = join(projectDir, 'node_modules');
  mkdirSync(join(dir, 'node_modules'));
  for (const entry of readdirSync(packages)) {
    if (['.vite', '.vite-temp', '.hexlod-lockfile.sha256'].includes(entry)) continue;
    symlinkSync(join(packages, entry), join(dir, 'node_modules', entry));
  }
  // The stamp scripts/setup.sh writes after `npm ci`: these packages are the lockfile's.
  const lockSha = createHash('sha256').update(readFileSync(join(dir, 'package-lock.json'))).digest('hex');
  writeFileSync(join(dir, 'node_modules', '.hexlod-lockfile.sha256'), `${lockSha}\n`);
  return dir;
}

/**
 * Starts `./hexlod.sh view` in the copy on a free port, in its own process group, and waits for
 * its serving line and for the page to answer. Returns { url, output(), stop() }.
 */
async function startView() {
  const port = await freePort();
  const env = { ...process.env, HEXLOD_PORT: String(port) };
  delete env.DISPLAY; // no --open: nothing but the test's browser opens the page
  delete env.WAYLAND_DISPLAY;
  const child = spawn('./hexlod.sh', ['view'], { cwd: tree, env, detached: true, stdio: ['ignore', 'pipe', 'pipe'] });
  let text = '';
  child.stdout.on('data', (chunk) => { text += chunk; });
  child.stderr.on('data', (chunk) => { text += chunk; });
  const exited = new Promise((resolve) => child.on('exit', resolve));
  const stop = async () => {
    if (child.exitCode === null && child.signalCode === null) {
      process.kill(-child.pid, 'SIGTERM'); // the script's group: npx, Vite, or an em++ still at work
      const killer = setTimeout(() => process.kill(-child.pid, 'SIGKILL'), 10000);
      await exited;
      clearTimeout(killer);
    }
    servers.delete(stop);
  };
  servers.add(stop);

  const url = `http://127.0.0.1:${port}/`;
  const serving = `hexlod: [3/3] serving ${url}`;
  const deadline = Date.now() + 15 * 60000; // a full emcc build on a loaded 2-core machine
  for (;;) {
    if (child.exitCode !== null || child.signalCode !== null) assert.fail(`view exited early:\n${text}`);
    if (Date.now() > deadline) assert.fail(`view did not serve in 15 min:\n${text}`);
    if (text.includes(serving)) {
      const answer = await fetch(url).then((r) => r.status, () => null);
      if (answer === 200) break;
    }
    await new Promise((resolve) => setTimeout(resolve, 250));
  }
  return { url, output: () => text, stop };
}

before(() => {
  mkdirSync(outDir, { recursive: true });
  tree = copyRepository();
});
after(async () => {
  for (const stop of [...servers]) await stop();
  if (tree) rmSync(tree, { recursive: true, force: true });
});

test('view in a tree without build/ builds only the page module, and its page draws the default terrain', { timeout: 25 * 60000 }, async () => {
  const view = await startView();
  const browser = await launchChromium();
  try {
    const { page, problems } = await openPage(browser, `${view.url}?budget=40`);
    await pageReady(page).catch((error) => assert.fail(`${error.message}\npage: ${problems.join('\n')}\nview: ${view.output()}`));
    const state = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error,
      name: window.hexlod.terrain?.name }));
    assert.equal(state.status, 'ready', `page status: ${state.error}`);
    assert.equal(state.name, 'globe_himalaya_2048.png');
    // The HUD's summary line counts the triangles drawn, as a person reads it.
    await page.waitForFunction(() => {
      const m = /([\d,]+) triangles/.exec(document.getElementById('hud')?.textContent ?? '');
      return m && Number(m[1].replaceAll(',', '')) > 10000;
    }, null, { timeout: 120000 });
    const stats = pixelStats(await page.screenshot({ path: `${outDir}/view-command.png` }));
    assert.ok(stats.colours > 200, `only ${stats.colours} distinct colours: the terrain is not drawn`);
    assert.ok(stats.luminanceStd > 12, `luminance spread ${stats.luminanceStd.toFixed(1)}: a flat image`);
    // On the curved Earth the far ground lies lower, under more haze: 6 to 7 % of warm rock here.
    assert.ok(stats.groundFraction > 0.05, `${(100 * stats.groundFraction).toFixed(1)} % ground colours`);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    await view.stop();
  }

  const output = view.output();
  assert.match(output, /^hexlod: \[1\/3\] packages ready \(\d+\.\d s\)$/m);
  assert.doesNotMatch(output, /installing/, 'the stamped node_modules counts as installed');
  assert.match(output, /^hexlod: \[2\/3\] page core built \(\d+\.\d s\)$/m);
  assert.match(output, /^hexlod: \[3\/3\] serving http:\/\/127\.0\.0\.1:\d+\/ /m);
  // Only the page's module was built: no native build, no Node module, no tests, no site.
  assert.deepEqual(readdirSync(join(tree, 'build')), ['wasm']);
  assert.ok(['hexlod_core.mjs', 'hexlod_core.wasm'].every((f) => readdirSync(join(tree, 'build/wasm')).includes(f)));
  assert.ok(!existsSync(join(tree, 'dist')), 'view made no dist/');
});

test('view again with nothing changed skips the build', { timeout: 10 * 60000 }, async (t) => {
  const wasm = join(tree, 'build/wasm/hexlod_core.wasm');
  if (!existsSync(wasm)) return t.skip('the first run did not build the module');
  const built = statSync(wasm).mtimeMs;
  const view = await startView();
  await view.stop();
  assert.match(view.output(), /^hexlod: \[2\/3\] page core up to date \(\d+\.\d s\)$/m);
  assert.equal(statSync(wasm).mtimeMs, built, 'the module was not written again');
  assert.ok(lstatSync(join(tree, 'node_modules/vite')).isSymbolicLink(), 'node_modules is still the links');
});
