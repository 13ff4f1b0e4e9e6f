// Walk camera: first person at an eye height above the ground. The eye never goes below
// max(drawn surface, full-resolution field) + eye height, also while the mesh refines: the
// page calls settle() after every LOD update, when the drawn surface may have moved.
import { FlyCamera } from './fly.js';

const WALK_SPEED = 1.4; // metres per second, a person's pace
const FAST = 40;        // shift: a fast vehicle
// The view's pitch when the walk takes over from another camera, radians: about 9 degrees down
// to 6 up, so the horizon is in view whatever the other camera looked at.
const WALK_START_PITCH_LOW = -0.15, WALK_START_PITCH_HIGH = 0.1;

export class WalkCamera extends FlyCamera {
  constructor() {
    super();
    this.mode = 'walk';
    this.eyeHeight = 2; // metres above the ground (drawn metres)
  }

  /** Walking speed; the field's spacing sets a floor so that a coarse grid can be crossed. */
  speed(fast) {
    return Math.max(WALK_SPEED, this.world.spacing * 0.05) * (fast ? FAST : 1);
  }

  /** Moves in the ground plane (looking up or down does not change the pace), then settles. */
  move(seconds, move, fast) {
    const step = this.speed(fast) * seconds;
    const s = Math.sin(this.yaw), c = Math.cos(this.yaw);
    // Stay on the field (standAt): walking off its edge would leave nothing under the feet.
    this.standAt(this.position[0] + step * (move.forward * -s + move.right * c),
      this.position[2] + step * (move.forward * -c - move.right * s));
  }

  /** Puts the eye exactly eyeHeight above the floor under it (world.floor: field and drawn surface). */
  settle() {
    this.position[1] = this.world.floor(this.position[0], this.position[2]) + this.eyeHeight;
  }

  /** The floor is eyeHeight below by construction (the field may lie lower under a coarse mesh). */
  clearance() {
    return this.eyeHeight;
  }

  /** Stands on the ground at (x, z), on the field, keeping the view direction. */
  standAt(x, z) {
    this.position[0] = Math.min(Math.max(x, 0), this.world.extentX);
    this.position[2] = Math.min(Math.max(z, 0), this.world.extentZ);
    this.settle();
  }

  copyPose(other) {
    super.copyPose(other);
    // A person who starts walking looks ahead at the landscape, with the horizon in view: from
    // a camera that looked down on the terrain, -0.6 rad showed only the ground at the feet.
    this.pitch = Math.min(Math.max(this.pitch, WALK_START_PITCH_LOW), WALK_START_PITCH_HIGH);
    this.standAt(this.position[0], this.position[2]);
  }
}
