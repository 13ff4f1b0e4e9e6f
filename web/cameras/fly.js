// Fly camera: free flight, WASD or the arrows to move, Q/E (or PageDown/PageUp) down and up,
// mouse drag to look; the speed scales with the height above the ground, shift for fast.
import { mat4, vec3 } from 'gl-matrix';
import { FOV_Y, clearanceOf, emptyWorld, finishMatrices } from './clip_planes.js';

const LOOK_LIMIT = 1.55;     // radians up or down
const SPEED_PER_METRE = 0.8; // metres per second for each metre of height above the ground
const FAST = 6;              // shift multiplies the speed

export class FlyCamera {
  constructor() {
    this.mode = 'fly';
    this.position = new Float64Array(3); // metres (heights exaggerated); doubles: a float is 4 m apart on a world field
    this.yaw = 0;                  // radians, 0 looks north (towards -z), as the orbit camera
    this.pitch = -0.3;             // radians above the horizon (negative: looking down)
    this.fovY = FOV_Y;
    this.target = new Float64Array(3);   // a point straight ahead, for the LOD camera
    this.direction = new Float64Array(3);
    this.view = mat4.create();
    this.projection = mat4.create();
    this.viewProjection = mat4.create();
    this.up = vec3.fromValues(0, 1, 0);
    this.world = emptyWorld();
  }

  /** Takes the pose of another camera (eye, and where it looks). */
  copyPose(other) {
    vec3.copy(this.position, other.position);
    const d = vec3.subtract(vec3.create(), other.target, other.position);
    const length = Math.max(vec3.length(d), 1e-9);
    this.yaw = Math.atan2(-d[0], -d[2]);
    this.pitch = Math.max(-LOOK_LIMIT, Math.min(LOOK_LIMIT, Math.asin(d[1] / length)));
  }

  /** Mouse look by (dx, dy) pixels. */
  look(dx, dy) {
    this.yaw -= dx * 0.003;
    this.pitch = Math.max(-LOOK_LIMIT, Math.min(LOOK_LIMIT, this.pitch - dy * 0.003));
  }

  /** Metres per second at the current height above the ground. */
  speed(fast) {
    const clearance = Math.max(clearanceOf(this.position, this.world), this.world.spacing * 0.05);
    return clearance * SPEED_PER_METRE * (fast ? FAST : 1);
  }

  /**
   * Moves for `seconds` with the held keys: move = {forward, right, up} each -1, 0 or 1.
   * Flying never enters the ground: the eye stays a little above it.
   */
  move(seconds, move, fast) {
    const step = this.speed(fast) * seconds;
    const s = Math.sin(this.yaw), c = Math.cos(this.yaw), cp = Math.cos(this.pitch), sp = Math.sin(this.pitch);
    this.position[0] += step * (move.forward * -s * cp + move.right * c);
    this.position[1] += step * (move.forward * sp + move.up);
    this.position[2] += step * (move.forward * -c * cp - move.right * s);
    this.keepAboveGround(this.world.spacing * 0.02);
  }

  /** Lifts the eye to at least `clearance` metres above the ground under it. */
  keepAboveGround(clearance) {
    const below = clearance - clearanceOf(this.position, this.world);
    if (below > 0) this.position[1] += below;
  }

  /** Recomputes the matrices for a viewport aspect ratio (width / height). */
  update(aspect) {
    const cp = Math.cos(this.pitch);
    vec3.set(this.direction, -Math.sin(this.yaw) * cp, Math.sin(this.pitch), -Math.cos(this.yaw) * cp);
    const clearance = this.clearance();
    const lookDistance = Math.max(clearance, this.world.spacing) * 4;
    vec3.scaleAndAdd(this.target, this.position, this.direction, lookDistance);
    mat4.lookAt(this.view, this.position, this.target, this.up);
    finishMatrices(this, aspect, this.world, lookDistance, clearance);
  }

  /** Height of the eye above the ground. */
  clearance() {
    return clearanceOf(this.position, this.world);
  }
}
