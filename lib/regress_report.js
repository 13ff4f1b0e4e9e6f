// What `hexlod regress` writes about a run: the verdict line of each flight, summary.txt,
// report.html (per flight its changes, a table of per-frame figures, and per capture the
// reference, the new image and the diff, labelled, with a slider and a diff overlay to compare),
// a JUnit XML file for CI test reporters and a JSON file for scripts. All read one run object
// (lib/regress.js): {options, error, results, exitCode, startedAt, seconds}.
import { RECORD_FIELDS } from '../web/app/deterministic/flight.js';

/** '1 flight', '2 flights'. */
export const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;

const VERDICT_WORDS = {
  pass: 'passed', regression: 'regressed', 'no-reference': 'had no reference', 'bad-input': 'had bad input',
  error: 'could not run', updated: 'written as references',
};

/** One line per flight: its verdict and why. */
export function flightLine(result) {
  const captures = result.captures.length ? `, ${plural(result.captures.length, 'capture')}` : ', figures only';
  const counts = `${plural(result.frames, 'frame')}${captures}`;
  switch (result.verdict) {
    case 'pass': {
      const drifted = result.captures.filter((c) => c.changed);
      const changed = result.changes.length ? `; the flight changed since the reference (${result.changes.join(', ')}), its results did not` : '';
      if (!result.captures.length) return `ok: ${counts}${changed}`;
      if (drifted.length === 0) return `ok: ${counts}; pixels identical${changed}`;
      return `ok: ${counts}; pixels changed below the tolerance: ${drifted.map((c) => `frame ${c.frame} ${c.summary}`).join('; ')}${changed}`;
    }
    case 'updated': return `reference written: ${counts}`;
    case 'regression': return `REGRESSION: ${result.problems.join('; ')}`;
    case 'no-reference': return `NO REFERENCE: ${result.problems.join('; ')}`;
    case 'bad-input': return `BAD INPUT: ${result.problems.join('; ')}`;
    default: return `ERROR: ${result.problems.join('; ')}`;
  }
}

/** The first line of a run: what happened to how many flights. */
export function headline(run) {
  if (run.error && run.results.length === 0) return `hexlod regress: stopped: ${run.error.message}`;
  const byVerdict = new Map();
  for (const r of run.results) byVerdict.set(r.verdict, (byVerdict.get(r.verdict) ?? 0) + 1);
  const parts = [...byVerdict].map(([verdict, n]) => `${n} ${VERDICT_WORDS[verdict]}`);
  const stopped = run.error ? `; stopped: ${run.error.message}` : '';
  return `hexlod regress: ${plural(run.results.length, 'flight')}: ${parts.join(', ')}${run.options.nodeOnly ? ' (Node only: figures, no pixels)' : ''}${stopped}`;
}

/** summary.txt: the headline, each flight's verdict with its details, where things are. No times: runs compare equal. */
export function summaryText(run) {
  const lines = [headline(run)];
  for (const r of run.results) {
    lines.push(`  ${r.name}: ${flightLine(r)}`);
    for (const detail of [...r.details, ...r.frameLines]) lines.push(`    ${detail}`);
  }
  if (run.options.refs) lines.push(`references ${run.options.refs}`);
  lines.push(`report     ${run.options.out}/report.html`);
  lines.push(`exit code  ${run.exitCode}`);
  return lines.join('\n') + '\n';
}

const escapeXml = (text) => String(text)
  // XML 1.0 allows no control characters but tab, newline and carriage return.
  .replace(/[\u0000-\u0008\u000b\u000c\u000e-\u001f]/g, '')
  .replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&apos;' }[c]));
const escapeHtml = escapeXml;

/** JUnit XML: one test case per flight; regressions are failures, everything else that did not pass an error. */
export function junitXml(run) {
  const cases = run.results.map((r) => {
    const time = (r.seconds ?? 0).toFixed(3);
    const head = `    <testcase classname="hexlod.regress" name="${escapeXml(r.name)}" file="${escapeXml(r.flightPath)}" time="${time}"`;
    if (r.verdict === 'pass' || r.verdict === 'updated') {
      return `${head}>\n      <system-out>${escapeXml(flightLine(r))}</system-out>\n    </testcase>`;
    }
    const tag = r.verdict === 'regression' ? 'failure' : 'error';
    const body = [flightLine(r), ...r.details, ...r.frameLines].join('\n');
    return `${head}>\n      <${tag} type="${r.verdict}" message="${escapeXml(r.problems[0] ?? r.verdict)}">${escapeXml(body)}</${tag}>\n    </testcase>`;
  });
  if (run.error) {
    cases.push(`    <testcase classname="hexlod.regress" name="(run)" time="0">\n      <error type="${run.error.kind}" message="${escapeXml(run.error.message)}"/>\n    </testcase>`);
  }
  const failures = run.results.filter((r) => r.verdict === 'regression').length;
  const errors = cases.length - failures - run.results.filter((r) => r.verdict === 'pass' || r.verdict === 'updated').length;
  const counts = `tests="${cases.length}" failures="${failures}" errors="${errors}" skipped="0" time="${run.seconds.toFixed(3)}"`;
  return `<?xml version="1.0" encoding="UTF-8"?>
<testsuites name="hexlod regress" ${counts}>
  <testsuite name="hexlod regress" ${counts} timestamp="${run.startedAt}">
${cases.join('\n')}
  </testsuite>
</testsuites>
`;
}

/** The JSON document: the run without image data. */
export function jsonReport(run) {
  return JSON.stringify({
    tool: 'hexlod regress',
    exitCode: run.exitCode,
    summary: headline(run),
    error: run.error,
    startedAt: run.startedAt,
    seconds: Number(run.seconds.toFixed(3)),
    options: run.options,
    flights: run.results.map((r) => ({
      name: r.name, flightPath: r.flightPath, dem: r.dem, verdict: r.verdict, line: flightLine(r), problems: r.problems,
      changes: r.changes, details: r.details, frameLines: r.frameLines, frames: r.frames, differingFrames: r.differingFrames,
      captures: r.captures, seconds: Number((r.seconds ?? 0).toFixed(3)),
    })),
  }, null, 1) + '\n';
}

const TABLE_FIELDS = ['hash', ...RECORD_FIELDS];
const MAX_TABLE_ROWS = 400; // longer flights list their differing frames only

/** The per-frame figures: the new run's, with reference → new where they differ. */
function figureTable(r) {
  const actual = r.table?.actual;
  if (!actual?.length) return '';
  const reference = r.table.reference;
  const differs = (f) => reference && TABLE_FIELDS.some((k) => reference[f]?.[k] !== actual[f][k]);
  const frames = actual.length <= MAX_TABLE_ROWS ? actual.map((_, f) => f) : actual.map((_, f) => f).filter(differs);
  const cell = (f, key) => {
    const now = actual[f][key], was = reference?.[f]?.[key];
    if (!reference || was === now) return `<td>${escapeHtml(now)}</td>`;
    return `<td class="d">${escapeHtml(was ?? '–')} → ${escapeHtml(now)}</td>`;
  };
  const rows = frames.map((f) => `<tr${differs(f) ? ' class="d"' : ''}><td>${f}</td>${TABLE_FIELDS.map((k) => cell(f, k)).join('')}</tr>`).join('\n');
  const note = frames.length < actual.length ? `<p>${plural(frames.length, 'frame')} of ${actual.length} differ; only those are listed.</p>` : '';
  const anyDiffers = frames.some(differs);
  const caption = !reference ? 'Per-frame figures' : anyDiffers ? 'Per-frame figures, reference → new where they differ'
    : 'Per-frame figures, every one as the reference\'s';
  return `<details${anyDiffers ? ' open' : ''}><summary>${caption}</summary>${note}
<table><tr><th>frame</th>${TABLE_FIELDS.map((k) => `<th>${k}</th>`).join('')}</tr>
${rows}</table></details>`;
}

/** One capture: labelled images and a comparer (slider between reference and new, diff overlay). */
function captureFigure(c) {
  const label = (src, text) => `<figure><a href="${escapeHtml(src)}"><img src="${escapeHtml(src)}" alt="${text}"></a><figcaption>${text}</figcaption></figure>`;
  const images = [
    c.images.reference ? label(c.images.reference, 'reference') : '<figure class="none"><span>no reference image</span><figcaption>reference</figcaption></figure>',
    label(c.images.actual, 'new'),
    c.images.diff ? label(c.images.diff, 'diff') : '',
  ].join('');
  const comparer = c.images.reference && c.images.diff ? `
    <div class="compare" style="--split:50%;--overlay:0">
      <img src="${escapeHtml(c.images.reference)}" alt="reference">
      <img class="new" src="${escapeHtml(c.images.actual)}" alt="new">
      <img class="overlay" src="${escapeHtml(c.images.diff)}" alt="diff overlay">
      <div class="tags"><span>reference</span><span>new</span></div>
    </div>
    <label>reference ◀ slide ▶ new <input type="range" min="0" max="100" value="50" oninput="this.closest('.capture').querySelector('.compare').style.setProperty('--split', this.value + '%')"></label>
    <label>diff overlay <input type="range" min="0" max="100" value="0" oninput="this.closest('.capture').querySelector('.compare').style.setProperty('--overlay', this.value / 100)"></label>` : '';
  return `<div class="capture ${c.verdict === 'pass' ? 'ok' : 'bad'}"><h3>frame ${c.frame}: ${escapeHtml(c.verdict === 'pass' ? 'ok' : 'differs')}</h3>
    <p>${escapeHtml(c.summary ?? '')}</p>${c.tolerance ? `<p class="legend">tolerance: threshold ${c.tolerance.threshold}, ${c.tolerance.maxDiffPixels} pixels or ${(100 * c.tolerance.maxDiffPixelRatio).toFixed(3)} %, anti-aliasing ${c.tolerance.antialiasing}${c.tolerance.masks.length ? `, ${plural(c.tolerance.masks.length, 'mask')}` : ''}</p>` : ''}
    <div class="row">${images}</div>${comparer}</div>`;
}

/** report.html, beside the images it shows. */
export function htmlReport(run) {
  const sections = run.results.map((r) => {
    const changes = r.changes.length ? `<p><b>The flight changed since the reference:</b> ${escapeHtml(r.changes.join('; '))}</p>` : '';
    const details = r.details.length ? `<ul>${r.details.map((d) => `<li>${escapeHtml(d)}</li>`).join('')}</ul>` : '';
    return `<section class="${r.verdict}"><h2>${escapeHtml(r.name)}: ${escapeHtml(VERDICT_WORDS[r.verdict])}</h2>
      <p class="legend">flight ${escapeHtml(r.flightPath)}${r.dem ? ` · height field ${escapeHtml(r.dem)}` : ''}</p>
      <p>${escapeHtml(flightLine(r))}</p>${changes}${details}${figureTable(r)}
      ${r.captures.map(captureFigure).join('\n')}</section>`;
  }).join('\n');
  const stopped = run.error ? `<section class="error"><h2>The run stopped</h2><p>${escapeHtml(run.error.message)}</p></section>` : '';
  return `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>${escapeHtml(headline(run))}</title>
<style>
body{font:14px system-ui,sans-serif;margin:16px;background:#f4f5f7;color:#222}
section{background:#fff;margin:12px 0;padding:8px 12px;border-left:6px solid #3a3}
section.regression,section.error,section.bad-input,section.no-reference{border-color:#d33}
.row{display:flex;gap:10px;flex-wrap:wrap}figure{margin:0}figcaption{text-align:center;color:#444}
img{image-rendering:pixelated;border:1px solid #ccc;max-width:30vw;display:block}
figure.none span{display:flex;align-items:center;justify-content:center;width:200px;height:100px;color:#a00;border:1px dashed #a00}
.legend{color:#666}.capture{margin:10px 0;padding-top:4px;border-top:1px solid #eee}.capture.bad h3{color:#c22}
.compare{position:relative;display:inline-block;margin-top:8px}.compare img{max-width:60vw}
.compare .new,.compare .overlay{position:absolute;left:0;top:0;width:100%;height:100%}
.compare .new{clip-path:inset(0 0 0 var(--split))}.compare .overlay{opacity:var(--overlay);pointer-events:none}
.compare .tags{position:absolute;top:4px;left:4px;right:4px;display:flex;justify-content:space-between;pointer-events:none}
.compare .tags span{background:#000a;color:#fff;padding:1px 6px;border-radius:3px}
label{display:block;margin:4px 0}table{border-collapse:collapse;font:12px ui-monospace,monospace}
td,th{border:1px solid #ddd;padding:1px 5px;text-align:right}tr.d{background:#fff4f4}td.d{background:#fdd;font-weight:bold}
</style></head><body>
<h1>${escapeHtml(headline(run))}</h1>
<p class="legend">Mesh hashes and per-frame figures are compared exactly, with Node's replay and with the reference.
Pixels: pixelmatch's perceptual distance per pixel against the threshold; a capture fails when more pixels differ than its tolerance allows.
Diff images: red differs, yellow anti-aliased (left out unless counted), orange changed below the threshold, blue masked.</p>
${stopped}${sections}</body></html>
`;
}
