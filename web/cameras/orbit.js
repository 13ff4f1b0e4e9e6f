// Orbit camera: looks at a target point from a distance, yaw and pitch; the mouse orbits
// (drag), pans (right or shift drag), zooms (wheel), and a double click orbits around the
// point under the pointer. Scratch objects are reused so a frame allocates nothing.
import { mat4, vec3 } from 'gl-matrix';
import { FOV_Y, clearanceOf, emptyWorld, finishMatrices } from './clip_planes.js';

export const MIN_PITCH = 0.02;
export const MAX_PITCH = 1.55;

export class OrbitCamera {
  constructor() {
    this.mode = 'orbit';
    this.target = new Float64Array(3); // metres; doubles: a float is 4 m apart on a world field
    this.distance = 1000;        // metres from the target
    this.yaw = 0;                // radians, 0 looks north (towards -z)
    this.pitch = 0.5;            // radians above the horizon
    this.fovY = FOV_Y;
    this.position = new Float64Array(3);
    this.view = mat4.create();
    this.projection = mat4.create();
    this.viewProjection = mat4.create();
    this.up = vec3.fromValues(0, 1, 0);
    this.world = emptyWorld();
  }

  /** Orbits around a new target point from now on, the eye staying at `eye` (default: where it is). */
  lookAround(x, y, z, eye = null) {
    if (!eye) this.update(this.aspect ?? 1);
    const [ex, ey, ez] = eye ?? this.position;
    const dx = ex - x, dy = ey - y, dz = ez - z;
    vec3.set(this.target, x, y, z);
    this.distance = Math.max(Math.hypot(dx, dy, dz), 1e-3);
    this.yaw = Math.atan2(dx, dz);
    this.pitch = Math.min(MAX_PITCH, Math.max(MIN_PITCH, Math.asin(dy / this.distance)));
  }

  /** Recomputes the matrices for a viewport aspect ratio (width / height). */
  update(aspect) {
    const cp = Math.cos(this.pitch);
    vec3.set(this.position,
      this.target[0] + this.distance * cp * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * cp * Math.cos(this.yaw));
    mat4.lookAt(this.view, this.position, this.target, this.up);
    finishMatrices(this, aspect, this.world, this.distance, clearanceOf(this.position, this.world));
  }

  /**
   * Raises the eye (a steeper pitch around the same target, then a longer distance) until it
   * is `clearance` metres above the ground under it; for a world whose heights just changed
   * (a new exaggeration or cell size).
   */
  keepAboveGround(clearance) {
    this.update(this.aspect ?? 1);
    while (this.pitch < MAX_PITCH && clearanceOf(this.position, this.world) < clearance) {
      this.pitch = Math.min(MAX_PITCH, this.pitch + 0.02);
      this.update(this.aspect ?? 1);
    }
    // Straight above the target and still in a hill beside it: back away from the target.
    for (let k = 0; k < 100 && clearanceOf(this.position, this.world) < clearance; ++k) {
      this.distance *= 1.25;
      this.update(this.aspect ?? 1);
    }
  }

  /** Drag by (dx, dy) pixels: orbit, or pan the target in the ground plane. */
  drag(dx, dy, pan) {
    if (pan) {
      const s = this.distance * 0.0015;
      const c = Math.cos(this.yaw), n = Math.sin(this.yaw);
      this.target[0] -= (dx * c - dy * n) * s;
      this.target[2] -= (dx * n + dy * c) * s;
    } else {
      this.yaw -= dx * 0.005;
      this.pitch = Math.min(MAX_PITCH, Math.max(MIN_PITCH, this.pitch + dy * 0.005));
    }
  }

  /** Zoom by a factor (< 1 comes closer), never into the ground under the eye. */
  zoom(factor) {
    this.distance = Math.max(this.distance * factor, 1e-2);
  }
}
