// A short seeded run of the teleport benchmark (bench/teleports.js) for CI: 300 camera
// jumps over three fixtures, the mesh invariants and the stream's watertightness checked after
// every LOD update, absurd cameras refused without a trace, and the screen error within tau
// every time the mesh converged. The figures must add up, so that a check that stopped running
// fails here too.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));
const FIELDS = ['volcano_maungawhau.f32', 'jacksboro_fault.png', 'grandcanyon_512.png'].map((f) => `tests/fixtures/${f}`).join(',');

test('300 seeded teleports over three fixtures: every check passes and the figures add up', () => {
  const run = spawnSync(process.execPath, ['bench/teleports.js', '--teleports', '300', '--seed', '1', '--per-terrain', '100',
    '--converge-every', '25', '--fields', FIELDS], { cwd: root, encoding: 'utf8', timeout: 600000 });
  assert.equal(run.status, 0, `${run.stdout}\n${run.stderr}`);
  const figure = (label) => {
    const match = new RegExp(`^\\s+${label}\\s+(\\d+)$`, 'm').exec(run.stdout);
    assert.ok(match, `'${label}' in\n${run.stdout}`);
    return Number(match[1]);
  };
  assert.equal(figure('teleports'), 300);
  assert.equal(figure('failures'), 0);
  const convergences = figure('convergences checked');
  assert.equal(convergences, 300 / 25);
  assert.equal(figure('mesh invariant checks passed'), 300 + convergences, 'after every teleport and every convergence');
  assert.equal(figure('stream watertightness checks passed'), 300 + convergences);
  assert.equal(figure('absurd cameras refused, mesh unchanged'), Math.floor(300 / 16));
  assert.equal(figure('within tau once converged') + figure('under a triangle cap \\(no bound\\)'), convergences);
  assert.ok(figure('largest mesh \\(triangles\\)') > 10000, 'some teleports refine well past the base mesh');
  assert.match(run.stdout, /no failures/);
});

test('the teleport benchmark refuses a bad command line with exit code 2', () => {
  const run = spawnSync(process.execPath, ['bench/teleports.js', '--teleports', 'many'], { cwd: root, encoding: 'utf8' });
  assert.equal(run.status, 2);
  assert.match(run.stderr, /--teleports must be an integer/);
});
