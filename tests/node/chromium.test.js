// Which Chromium `hexlod regress` and the browser tests run (lib/chromium.js findChromium), on
// fake folders: the one named (--chromium, CHROMIUM_PATH), else Debian's, else the newest of
// Playwright's downloads in either layout; none gives one line saying how to get one.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { EnvironmentError, findChromium, playwrightBrowsersDir, playwrightChromiums } from '../../lib/chromium.js';

/** A fake machine: a home, a system path and files at the given paths below its folder. */
function machine(files) {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-chromium-'));
  for (const file of files) {
    mkdirSync(dirname(join(dir, file)), { recursive: true });
    writeFileSync(join(dir, file), '#!/bin/sh\n');
  }
  return { dir, home: join(dir, 'home'), system: join(dir, 'usr/bin/chromium'), close: () => rmSync(dir, { recursive: true, force: true }) };
}

const NONE_FOUND = /^no Chromium found \(not at .*usr\/bin\/chromium, none of Playwright's in .*\): install one with apt-get install chromium \(Debian\) or npx playwright-core install chromium, or give --chromium PATH$/;

test('the named Chromium comes first: --chromium, then CHROMIUM_PATH, and a missing one is not replaced by another', () => {
  const m = machine(['usr/bin/chromium', 'mine/chrome', 'env/chrome']);
  try {
    const env = { CHROMIUM_PATH: join(m.dir, 'env/chrome') };
    assert.equal(findChromium({ given: join(m.dir, 'mine/chrome'), env, home: m.home, system: m.system }), join(m.dir, 'mine/chrome'));
    assert.equal(findChromium({ env, home: m.home, system: m.system }), join(m.dir, 'env/chrome'));
    assert.throws(() => findChromium({ given: join(m.dir, 'nope'), env, home: m.home, system: m.system }), (error) => error instanceof EnvironmentError &&
      error.message === `no Chromium at ${join(m.dir, 'nope')} (--chromium): name the Chromium program, or install one with apt-get install chromium (Debian) or npx playwright-core install chromium`);
    assert.throws(() => findChromium({ env: { CHROMIUM_PATH: join(m.dir, 'mine') }, home: m.home, system: m.system }),
      { name: 'Error', message: /^no Chromium at .*mine \(CHROMIUM_PATH\): name the Chromium program/ }); // a folder is no program
  } finally {
    m.close();
  }
});

test("Debian's Chromium before Playwright's", () => {
  const m = machine(['usr/bin/chromium', 'home/.cache/ms-playwright/chromium-1255/chrome-linux64/chrome']);
  try {
    assert.equal(findChromium({ env: {}, home: m.home, system: m.system }), m.system);
  } finally {
    m.close();
  }
});

test("Playwright's downloads: the newest full Chromium, in the old layout or Chrome for Testing's, before the headless shell", () => {
  const m = machine([
    'pw/chromium-1091/chrome-linux/chrome',
    'pw/chromium-1255/chrome-linux64/chrome',
    'pw/chromium_headless_shell-1300/chrome-headless-shell-linux64/chrome-headless-shell',
    'pw/chromium-999x/chrome-linux/chrome', // not a revision
    'pw/firefox-1572/firefox/firefox',
  ]);
  mkdirSync(join(m.dir, 'pw/chromium-1400/chrome-linux64/chrome'), { recursive: true }); // a folder, not the program
  try {
    const env = { PLAYWRIGHT_BROWSERS_PATH: join(m.dir, 'pw') };
    assert.deepEqual(playwrightChromiums(join(m.dir, 'pw')), [
      join(m.dir, 'pw/chromium-1255/chrome-linux64/chrome'),
      join(m.dir, 'pw/chromium-1091/chrome-linux/chrome'),
      join(m.dir, 'pw/chromium_headless_shell-1300/chrome-headless-shell-linux64/chrome-headless-shell'),
    ]);
    assert.equal(findChromium({ env, home: m.home, system: m.system }), join(m.dir, 'pw/chromium-1255/chrome-linux64/chrome'));
  } finally {
    m.close();
  }
});

test("Playwright's headless shell alone is found, in the user's cache (or XDG_CACHE_HOME) when PLAYWRIGHT_BROWSERS_PATH is not set", () => {
  const m = machine(['home/.cache/ms-playwright/chromium_headless_shell-1187/chrome-linux/headless_shell',
    'xdg/ms-playwright/chromium-1200/chrome-linux64/chrome']);
  try {
    assert.equal(findChromium({ env: {}, home: m.home, system: m.system }),
      join(m.home, '.cache/ms-playwright/chromium_headless_shell-1187/chrome-linux/headless_shell'));
    assert.equal(findChromium({ env: { XDG_CACHE_HOME: join(m.dir, 'xdg') }, home: m.home, system: m.system }),
      join(m.dir, 'xdg/ms-playwright/chromium-1200/chrome-linux64/chrome'));
  } finally {
    m.close();
  }
});

test('no Chromium anywhere: one line that says how to get one', () => {
  const m = machine(['home/.cache/ms-playwright/firefox-1572/firefox/firefox']);
  try {
    for (const env of [{}, { PLAYWRIGHT_BROWSERS_PATH: join(m.dir, 'empty') }, { PLAYWRIGHT_BROWSERS_PATH: '0' }]) {
      assert.throws(() => findChromium({ env, home: m.home, system: m.system }), (error) => {
        assert.ok(error instanceof EnvironmentError);
        assert.match(error.message, NONE_FOUND);
        assert.equal(error.message.split('\n').length, 1);
        return true;
      });
    }
    // PLAYWRIGHT_BROWSERS_PATH=0: the browsers inside the playwright-core package, as Playwright puts them.
    assert.match(playwrightBrowsersDir({ PLAYWRIGHT_BROWSERS_PATH: '0' }, m.home), /node_modules\/playwright-core\/\.local-browsers$/);
  } finally {
    m.close();
  }
});
