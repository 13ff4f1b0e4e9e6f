// The cameras keep their places in doubles: on a world field a float's metres are 4 m apart at
// the east edge, where a fly camera 3 m above the ground moves 4 cm a frame. In floats it would
// not move east at all (every step rounds back), and an orbit around a point there would circle
// a point 2 m away.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FlyCamera } from '../../web/cameras/fly.js';
import { OrbitCamera } from '../../web/cameras/orbit.js';

// A world field's size in flat metres: 1,296,000 x 626,400 samples at 30.87 x 30.87 m.
const world = { extentX: 4.0e7, extentZ: 1.93e7, low: 0, high: 9000, spacing: 30.87, ground: () => 800, floor: () => 800 };
const EAST = 3.7e7, NORTH = 5.0e6; // metres: 172° E, 45° N

test('a fly camera 3 m above a valley floor at a world field\'s east edge moves by its 4 cm steps', () => {
  const fly = new FlyCamera();
  fly.world = world;
  fly.position[0] = EAST + 0.3, fly.position[1] = 803, fly.position[2] = NORTH + 0.7;
  fly.yaw = -Math.PI / 2; // east
  fly.pitch = 0;
  const start = fly.position[0], seconds = 1 / 60, step = fly.speed(false) * seconds;
  assert.ok(step < 0.05, `a step of ${step} m`);
  for (let frame = 0; frame < 60; frame++) fly.move(seconds, { forward: 1, right: 0, up: 0 }, false);
  assert.ok(Math.abs(fly.position[0] - start - 60 * step) < 1e-6, `moved ${fly.position[0] - start} m east, expected ${60 * step}`);
  assert.equal(fly.position[2], NORTH + 0.7, 'not north or south');
  fly.update(16 / 9);
  assert.ok(Math.abs(fly.target[0] - fly.position[0] - 4 * world.spacing) < 1e-6, 'the point ahead is four sample spacings ahead');
});

test('an orbit camera around a point at a world field\'s east edge circles that point', () => {
  const orbit = new OrbitCamera();
  orbit.world = world;
  orbit.target[0] = EAST + 0.3, orbit.target[1] = 800, orbit.target[2] = NORTH + 0.7;
  orbit.distance = 5;
  orbit.pitch = 0.3;
  for (const yaw of [0, 1, 2, 3]) {
    orbit.yaw = yaw;
    orbit.update(16 / 9);
    const d = Math.hypot(orbit.position[0] - orbit.target[0], orbit.position[1] - orbit.target[1], orbit.position[2] - orbit.target[2]);
    assert.ok(Math.abs(d - 5) < 1e-6, `yaw ${yaw}: the eye is ${d} m from the point`);
  }
});
