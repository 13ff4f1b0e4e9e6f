// The page runs under a strict Content-Security-Policy: scripts from the site only,
// WebAssembly compiled from them, no inline script or style, fetches to any http(s) host. The
// default journey (open, the terrain on screen, drop a file, move the camera, reset, save a
// screenshot) runs on the dev server (the policy as a header and in the page, with Vite's client
// and its hot-reload connection) and on the built site from a plain static server (the <meta>
// alone), in a browser context that does not bypass the policy. No violation may be reported,
// and the policy must be in force: an inline script and an inline style are refused.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { startViewer, pageReady, terrainCoverage, dropFiles, terrainShown, nextFrame, outDir, projectDir } from '../../lib/page_harness.js';

const VIEWPORT = { width: 480, height: 300 };
const fixture = (name) => ({ name, bytes: readFileSync(`${projectDir}tests/fixtures/${name}`) });
/** The policy of public/index.html's <meta> (what the built site carries). */
const POLICY = /<meta http-equiv="Content-Security-Policy" content="([^"]+)"/.exec(readFileSync(`${projectDir}public/index.html`, 'utf8'))?.[1];

/** The orbit camera's pose, to tell a moved camera and a reset one. */
const pose = (page) => page.evaluate(() => {
  const { target, distance, yaw, pitch } = window.hexlod.rig.cameras.orbit;
  return { target: Array.from(target), distance, yaw, pitch };
});

for (const site of ['dev', 'built']) {
  test(`${site} site: the default journey under the Content-Security-Policy reports no violation; the policy is in force`, async () => {
    assert.ok(POLICY?.includes("script-src 'self' 'wasm-unsafe-eval'"), 'public/index.html carries the policy');
    const viewer = await startViewer({ site, hmr: site === 'dev', pixelRatio: 0.5 });
    const context = await viewer.browser.newContext({ viewport: VIEWPORT, acceptDownloads: true }); // bypassCSP stays off
    try {
      const page = await context.newPage();
      // Every violation the page reports, from before its first script runs.
      await page.addInitScript(() => {
        window.cspViolations = [];
        document.addEventListener('securitypolicyviolation', (e) => {
          window.cspViolations.push(`${e.effectiveDirective} blocked ${e.blockedURI || 'inline'} (${e.sourceFile}:${e.lineNumber})`);
        });
      });
      const problems = [], consoleText = [];
      page.on('console', (message) => {
        consoleText.push(message.text());
        if (message.type() === 'error' || /Content.Security.Policy/i.test(message.text())) problems.push(message.text());
      });
      page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
      const response = await page.goto(viewer.url);
      if (site === 'dev') assert.equal(response.headers()['content-security-policy'], POLICY, 'the dev server sends the policy as a header');
      else assert.equal(response.headers()['content-security-policy'], undefined, 'a plain static host: the <meta> alone');
      assert.equal(await page.getAttribute('meta[http-equiv="Content-Security-Policy"]', 'content'), POLICY);

      // Open: the default terrain on screen.
      await pageReady(page);
      assert.deepEqual(await page.evaluate(() => [window.hexlod.status, window.hexlod.error]), ['ready', null]);
      const opened = await terrainCoverage(page);
      assert.ok(opened.coverage > 0.3 && opened.colours > 50, `the default terrain on screen: ${JSON.stringify(opened)}`);
      // lil-gui's stylesheet comes from style.css, not an injected <style>: the panel is styled.
      assert.equal(await page.evaluate(() => getComputedStyle(document.querySelector('#panel .lil-root'))
        .getPropertyValue('--background-color').trim()), '#1f1f1f');

      // Drop a file.
      await dropFiles(page, [fixture('volcano_maungawhau.png'), fixture('volcano_maungawhau.json')]);
      await terrainShown(page, 'volcano_maungawhau.png');
      const dropped = await terrainCoverage(page);
      assert.ok(dropped.coverage > 0.1, `the dropped terrain on screen: ${JSON.stringify(dropped)}`);

      // Move the camera with the mouse, then reset it with R: to the view R gives before the move
      // (the pointer already on the canvas both times: its readout line in the HUD is part of the framing).
      await page.mouse.move(240, 150);
      await page.keyboard.press('r');
      await nextFrame(page);
      const framed = await pose(page);
      await page.mouse.down();
      await page.mouse.move(330, 170, { steps: 5 });
      await page.mouse.up();
      await nextFrame(page);
      assert.notDeepEqual(await pose(page), framed, 'the drag moved the camera');
      await page.keyboard.press('r');
      await nextFrame(page);
      assert.deepEqual(await pose(page), framed, 'R frames the terrain again');

      // A screenshot saved through a blob: link.
      const [download] = await Promise.all([page.waitForEvent('download'), page.evaluate(() => window.hexlod.screenshot(1))]);
      assert.match(download.suggestedFilename(), /^hexlod-volcano_maungawhau-1x\.png$/);
      await page.screenshot({ path: `${outDir}/csp-${site}.png` });

      if (site === 'dev') assert.ok(consoleText.includes('[vite] connected.'), "Vite's client and its hot-reload connection work");
      assert.deepEqual(await page.evaluate(() => window.cspViolations), [], 'no violation during the journey');
      assert.deepEqual(problems, []);

      // The policy is in force: an inline script does not run and an inline style does not apply,
      // and each is reported (so the empty list above means something).
      const refused = await page.evaluate(() => {
        const script = document.createElement('script');
        script.textContent = 'window.inlineScriptRan = true';
        document.head.append(script);
        const style = document.createElement('style');
        style.textContent = '#hud { visibility: hidden; }';
        document.head.append(style);
        return { scriptRan: window.inlineScriptRan === true, hudVisibility: getComputedStyle(document.getElementById('hud')).visibility };
      });
      assert.deepEqual(refused, { scriptRan: false, hudVisibility: 'visible' });
      await page.waitForFunction(() => window.cspViolations.length >= 2, null, { timeout: 5000 });
      const violations = await page.evaluate(() => window.cspViolations);
      assert.ok(violations.some((v) => v.startsWith('script-src-elem blocked inline')), violations.join('; '));
      assert.ok(violations.some((v) => v.startsWith('style-src-elem blocked inline')), violations.join('; '));
    } finally {
      await context.close();
      await viewer.close();
    }
  });
}
