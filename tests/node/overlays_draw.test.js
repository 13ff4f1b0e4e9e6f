// What the renderer gets of an overlay (web/render/overlays/overlay_geometry.js) and what the
// pointer finds (web/overlays/nearest_feature.js), on a known field: clamped lines at the
// full-resolution heights of every sample, lines aloft at the file's altitudes with a curtain
// down to the ground, markers at points, the parts off the field left out, and a 500 000-point
// track simplified for drawing within a fraction of the spacing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { overlayGeometry } from '../../web/render/overlays/overlay_geometry.js';
import { simplifyForDrawing } from '../../web/overlays/simplify_path.js';
import { nearestFeature } from '../../web/overlays/nearest_feature.js';
import { samplerOfArray } from '../../web/measure/field_sampler.js';
import { fillFrame } from '../../web/render/overlays/polygon_fill.js';

// A 101 x 101 field of 10 m: a ramp rising 2 m a metre eastwards and a bump, so heights differ everywhere.
const N = 101, SPACING = 10;
const heights = new Float32Array(N * N).map((_, k) => 2 * (k % N) * SPACING + 50 * Math.sin((Math.floor(k / N) * Math.PI) / 25));
const sampler = samplerOfArray(heights, N, N, SPACING, SPACING);
const path = (points, z = null) => {
  const x = Float64Array.from(points, (p) => p[0]), zz = Float64Array.from(points, (p) => p[1]);
  const inside = Uint8Array.from(points, ([px, pz]) => (px >= 0 && px <= 1000 && pz >= 0 && pz <= 1000 ? 1 : 0));
  return { placed: { x, z: zz, inside }, source: { x, y: zz, z: z && Float64Array.from(z), t: null } };
};
function placedOf(features) {
  return { features: features.map(({ kind, altitude = 'clamp', name = null, paths }) => ({
    feature: { kind, altitude, name, properties: {}, paths: paths.map((p) => p.source), polygons: kind === 'polygon' ? [paths.map((_, k) => k)] : null },
    paths: paths.map((p) => p.placed),
  })), offTerrain: 0, partlyOff: 0 };
}

test('a clamped line follows the full-resolution surface at every sample, and stops where it leaves the field', () => {
  const line = path([[5, 5], [505, 305], [1200, 305]]); // the last vertex lies off the field
  const g = overlayGeometry(placedOf([{ kind: 'line', paths: [line] }]), sampler);
  const n = g.segments.length / 6;
  assert.ok(n >= 100, `sampled at the spacing: ${n} segments`);
  for (let k = 0; k < n; k++) {
    for (const at of [0, 3]) {
      const [x, y, z] = g.segments.subarray(6 * k + at, 6 * k + at + 3);
      assert.ok(Math.abs(y - sampler.heightAt(x, z)) < 1e-3 * Math.max(1, Math.abs(y)), `segment ${k}: ${y} vs ${sampler.heightAt(x, z)}`);
      assert.ok(x >= 0 && x <= 1000 && z >= 0 && z <= 1000, 'nothing off the field');
    }
  }
  // Consecutive samples are at most a spacing apart on the map.
  for (let k = 0; k < n; k++) assert.ok(Math.hypot(g.segments[6 * k + 3] - g.segments[6 * k], g.segments[6 * k + 5] - g.segments[6 * k + 2]) <= SPACING + 1e-9);
});

test('a line aloft keeps the file\'s altitudes, with a curtain to the ground under each vertex; the user may clamp it', () => {
  const line = path([[100, 100], [300, 100], [300, 400]], [5000, 5100, 5200]);
  const placed = placedOf([{ kind: 'line', altitude: 'absolute', paths: [line] }]);
  const aloft = overlayGeometry(placed, sampler, { curtain: true });
  assert.deepEqual(Array.from(aloft.segments), [100, 5000, 100, 300, 5100, 100, 300, 5100, 100, 300, 5200, 400]);
  assert.equal(aloft.curtain.length, 2 * 18, 'two triangles a segment');
  const bottoms = [];
  for (let k = 0; k < aloft.curtain.length; k += 3) if (aloft.curtain[k + 1] < 4000) bottoms.push(aloft.curtain[k + 1] - sampler.heightAt(aloft.curtain[k], aloft.curtain[k + 2]));
  assert.ok(bottoms.length === 6 && bottoms.every((d) => Math.abs(d) < 1e-3), 'the curtain reaches the ground');
  const clamped = overlayGeometry(placed, sampler, { altitude: 'clamp', curtain: true });
  assert.equal(clamped.curtain.length, 0);
  assert.ok(clamped.segments.length / 6 > 40 && Math.abs(clamped.segments[1] - sampler.heightAt(100, 100)) < 1e-3);
});

test('points are markers at the ground with their names; off the field, none', () => {
  const g = overlayGeometry(placedOf([
    { kind: 'point', name: 'summit', paths: [path([[250, 750]])] },
    { kind: 'point', name: 'far away', paths: [path([[-50, 750]])] },
  ]), sampler);
  assert.deepEqual(Array.from(g.markers), [250, Math.fround(sampler.heightAt(250, 750)), 750]);
  assert.deepEqual(g.markerNames, ['summit']);
});

test('a polygon is outlined all round, and its fill lies over its box on the field', () => {
  const ring = path([[200, 200], [600, 200], [600, 500], [200, 500], [200, 200]]);
  const placed = placedOf([{ kind: 'polygon', paths: [ring] }]);
  const g = overlayGeometry(placed, sampler);
  assert.ok(g.segments.length / 6 >= 140, 'the four sides sampled at the spacing');
  const frame = fillFrame(placed, sampler);
  assert.deepEqual([frame.x0, frame.z0], [200, 200]);
  assert.equal(frame.pixel, SPACING / 4);
  assert.deepEqual([frame.width, frame.height], [160, 120]);
});

test('a 500 000-point track is simplified for drawing within a quarter of the spacing, ends kept', () => {
  const n = 500000, x = new Float64Array(n), z = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    const t = (2 * Math.PI * k) / n;
    x[k] = 500 + 400 * Math.sin(3 * t) + 0.5 * Math.sin(k);
    z[k] = 500 + 400 * Math.sin(2 * t + 0.5);
  }
  const kept = simplifyForDrawing(x, z, 2.5);
  assert.equal(kept[0], 0);
  assert.equal(kept[kept.length - 1], n - 1);
  assert.ok(kept.length < n / 20, `${kept.length} of ${n} kept`);
  // Every dropped vertex lies within the tolerance of the kept segment around it.
  for (let i = 1; i < kept.length; i++) {
    const a = kept[i - 1], b = kept[i], ex = x[b] - x[a], ez = z[b] - z[a], len2 = ex * ex + ez * ez;
    for (let k = a + 1; k < b; k += 97) {
      const t = Math.max(0, Math.min(1, ((x[k] - x[a]) * ex + (z[k] - z[a]) * ez) / len2));
      assert.ok(Math.hypot(x[a] + ex * t - x[k], z[a] + ez * t - z[k]) <= 2.5 + 1e-9);
    }
  }
  const line = { placed: { x, z, inside: new Uint8Array(n).fill(1) }, source: { x, y: z, z: null, t: null } };
  const g = overlayGeometry(placedOf([{ kind: 'line', paths: [line] }]), sampler);
  assert.equal(g.fileVertices, n);
  assert.equal(g.drawnVertices, kept.length);
});

test('the pointer finds the nearest line or point within reach, else the polygon around it', () => {
  const overlays = [{ visible: true, geometry: { picks: [
    { feature: 0, path: 0, kind: 'line', x: new Float64Array([0, 100]), z: new Float64Array([0, 0]), closed: false },
    { feature: 1, path: 0, kind: 'polygon', x: new Float64Array([200, 300, 300, 200]), z: new Float64Array([0, 0, 100, 100]), closed: true },
    { feature: 2, path: 0, kind: 'point', x: new Float64Array([250]), z: new Float64Array([50]), closed: false },
  ] } }];
  assert.equal(nearestFeature(overlays, 50, 3, 5).feature, 0);
  assert.equal(nearestFeature(overlays, 50, 8, 5), null);
  assert.equal(nearestFeature(overlays, 252, 50, 5).feature, 2, 'the marker before the polygon it stands in');
  assert.deepEqual(nearestFeature(overlays, 220, 80, 5), { overlay: 0, feature: 1, path: 0, kind: 'polygon', distance: 0 });
  assert.equal(nearestFeature([{ ...overlays[0], visible: false }], 50, 3, 5), null, 'a hidden overlay is not hovered');
});
