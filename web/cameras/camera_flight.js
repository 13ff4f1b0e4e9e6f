// A camera flight for the JS API's camera.flyTo(): the orbit camera moves its eye and target
// from where they are to where they are asked, eased in and out over a time. With
// prefers-reduced-motion, or no time, it jumps there at once. The rig steps it each frame.
import { vec3 } from 'gl-matrix';

/** 0..1 eased in and out (smoothstep). */
const ease = (t) => t * t * (3 - 2 * t);

export class CameraFlight {
  /**
   * @param {import('./orbit.js').OrbitCamera} orbit  the camera that flies
   * @param {{ position: number[], target: number[] }} to  metres in the world (x east, y up, z south)
   * @param {number} seconds
   */
  constructor(orbit, to, seconds) {
    orbit.update(orbit.aspect ?? 1);
    this.orbit = orbit;
    this.fromEye = Float64Array.from(orbit.position);
    this.fromTarget = Float64Array.from(orbit.target);
    this.toEye = Float64Array.from(to.position);
    this.toTarget = Float64Array.from(to.target);
    this.seconds = seconds;
    this.elapsed = 0;
    this.eye = new Float64Array(3); // doubles: a float is 4 m apart on a world field
    this.target = new Float64Array(3);
    this.done = null; // resolves the flyTo() promise
    this.finished = new Promise((resolve) => { this.done = resolve; });
    this.playing = true;
  }

  /** Moves the camera `seconds` further; false once it has arrived (and resolves its promise). */
  step(seconds) {
    this.elapsed = Math.min(this.seconds, this.elapsed + seconds);
    const t = this.seconds > 0 ? ease(this.elapsed / this.seconds) : 1;
    vec3.lerp(this.eye, this.fromEye, this.toEye, t);
    vec3.lerp(this.target, this.fromTarget, this.toTarget, t);
    this.orbit.lookAround(this.target[0], this.target[1], this.target[2], this.eye);
    if (t >= 1) this.stop(true);
    return this.playing;
  }

  /** Ends the flight where it is; its promise resolves to whether it arrived. */
  stop(arrived = false) {
    if (!this.playing) return;
    this.playing = false;
    this.done(arrived);
  }
}

/** Whether the person asked their system for less motion. */
export function prefersReducedMotion() {
  return typeof matchMedia === 'function' && matchMedia('(prefers-reduced-motion: reduce)').matches;
}
