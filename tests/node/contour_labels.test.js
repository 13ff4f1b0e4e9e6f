// Labels of the major contour lines (web/render/contours/labels.js), without a GPU: points found
// on the field's major levels, placed on the screen along their contour, kept apart, and hidden
// when the ground between the eye and them stands in the way.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mat4 } from 'gl-matrix';
import { LabelPlacer } from '../../web/render/contours/labels.js';
import { labelGlyphs, GLYPHS } from '../../web/render/contours/glyph_atlas.js';

const N = 64, SPACING = 10;
// A slope rising east: h = 0.5 x, so the contours run north-south and major levels (25 m) every 50 m.
const raw = new Float32Array(N * N).map((_, k) => 0.5 * (k % N) * SPACING);
const slope = { heightAt: (x) => 0.5 * Math.min(Math.max(x, 0), (N - 1) * SPACING) };

function camera(eye, target, width, height) {
  const view = mat4.lookAt(mat4.create(), eye, target, [0, 1, 0]);
  const projection = mat4.perspective(mat4.create(), (50 * Math.PI) / 180, width / height, 1, 1e5);
  return { viewProjection: mat4.multiply(mat4.create(), projection, view), position: Float32Array.from(eye) };
}

test('label points lie on the major levels, along their contour, with their heights as text', () => {
  const placer = new LabelPlacer();
  placer.findAnchors(raw, N, N, SPACING, SPACING, 1, 0, 25);
  assert.ok(placer.count > 20, `${placer.count} points`);
  for (let k = 0; k < placer.count; ++k) {
    assert.equal(placer.h[k] % 25, 0, 'a major level');
    assert.ok(Math.abs(0.5 * placer.x[k] - placer.h[k]) < 1e-6, 'on the field at its level');
    assert.ok(Math.abs(placer.tx[k]) < 1e-9 && Math.abs(Math.abs(placer.tz[k]) - 1) < 1e-9, 'along the contour (north-south)');
    const text = [...placer.glyphs.subarray(k * 8, k * 8 + placer.glyphCount[k])].map((g) => GLYPHS[g]).join('');
    assert.equal(text, String(placer.h[k]));
  }
  assert.deepEqual(labelGlyphs(-12.5).map((g) => GLYPHS[g]).join(''), '-12.5');
});

test('labels are placed upright on the screen, apart, and hidden behind the ground in front', () => {
  const placer = new LabelPlacer();
  placer.findAnchors(raw, N, N, SPACING, SPACING, 1, 0, 25);
  // From the south-west, above the slope: the labels are in sight.
  const cam = camera([-100, 700, 900], [320, 150, 320], 480, 300);
  const glyphs = placer.place(cam, 480, 300, 1, 1, slope);
  const shown = placer.labelsShown;
  assert.ok(shown >= 3, `${shown} labels shown`);
  for (let g = 0; g < glyphs; ++g) {
    const [x, y, ax] = placer.instances.subarray(g * 5, g * 5 + 3);
    assert.ok(x > 0 && x < 480 && y > 0 && y < 300, 'on the screen');
    assert.ok(ax > 0, 'reads left to right');
  }
  // A wall 2 km high between the eye and the field hides them all.
  const walled = { heightAt: (x, z) => (z > 700 && z < 760 ? 2000 : slope.heightAt(x, z)) };
  placer.place(cam, 480, 300, 1, 1, walled);
  assert.equal(placer.labelsShown, 0, 'none through the wall');
  // Its frames allocate nothing: the same arrays are filled again.
  const instances = placer.instances, occupied = placer.occupied;
  placer.place(cam, 480, 300, 1, 1, slope);
  assert.equal(placer.labelsShown, shown);
  assert.equal(placer.instances, instances);
  assert.equal(placer.occupied, occupied);
});
