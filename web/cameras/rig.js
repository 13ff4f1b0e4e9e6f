// The three cameras and their input: one is active; switching keeps the eye and the view
// direction. The mouse drags (orbit, pan, look), the wheel zooms, held keys move the fly and
// walk cameras every frame (step(seconds)), touch goes to touch.js.
import { OrbitCamera } from './orbit.js';
import { FlyCamera } from './fly.js';
import { WalkCamera } from './walk.js';
import { attachTouchControls } from './touch.js';
import { CameraFlight } from './camera_flight.js';
import { vec3 } from 'gl-matrix';
import { clearanceOf, emptyWorld } from './clip_planes.js';

export const CAMERA_MODES = ['orbit', 'fly', 'walk'];
// A camera more than this many eye heights above the ground hands the walk the ground it looked
// at, not the ground straight below it.
const WALK_FROM_ABOVE = 100;
const ORBIT_KEY_TURN = 200; // the orbit camera's drag pixels per second of a held key (1 rad/s)

// Held keys and what they do: [forward, right, up].
const MOVE_KEYS = {
  KeyW: [1, 0, 0], ArrowUp: [1, 0, 0], KeyS: [-1, 0, 0], ArrowDown: [-1, 0, 0],
  KeyD: [0, 1, 0], ArrowRight: [0, 1, 0], KeyA: [0, -1, 0], ArrowLeft: [0, -1, 0],
  KeyE: [0, 0, 1], PageUp: [0, 0, 1], KeyQ: [0, 0, -1], PageDown: [0, 0, -1],
};

export class CameraRig {
  /** @param {() => void} onChange asks for a frame */
  constructor(onChange) {
    this.cameras = { orbit: new OrbitCamera(), fly: new FlyCamera(), walk: new WalkCamera() };
    this.active = this.cameras.orbit;
    this.onChange = onChange;
    this.held = new Set(); // codes of the movement keys held down
    this.fast = false;
    this.move = { forward: 0, right: 0, up: 0 };
    // Adds a held key's movement to this.move: made once, so a frame's key loop makes no garbage.
    this.addMove = (code) => {
      const m = MOVE_KEYS[code];
      this.move.forward += m[0];
      this.move.right += m[1];
      this.move.up += m[2];
    };
    this.setWorld(emptyWorld());
    this.follow = null;      // a track being followed (track_follow.js), or null
    this.flight = null;      // the orbit camera's flight to a view asked by the JS API (camera_flight.js), or null
    this.verticalScale = 1;  // the exaggeration, for a followed track's heights
  }

  get mode() { return this.active.mode; }

  /** The terrain's extent, heights and ground (see clip_planes.js emptyWorld). */
  setWorld(world) {
    this.world = world;
    for (const camera of Object.values(this.cameras)) camera.world = world;
  }

  /**
   * Switches the camera, keeping the eye and the view direction where it can. Where the eye
   * cannot stay, the switch goes where a person would: walking starts on the ground the view
   * was centred on (from high above, the ground straight below is often the field's edge or
   * nothing in view), looking ahead; leaving a walk for the orbit camera brings its overview
   * back (its distance and pitch) around where the walk ended.
   */
  setMode(mode) {
    if (!CAMERA_MODES.includes(mode)) throw new Error(`unknown camera '${mode}' (orbit, fly or walk)`);
    const from = this.active, to = this.cameras[mode];
    if (from === to) return;
    from.update(from.aspect ?? 1);
    if (mode === 'orbit' && from.mode === 'walk') {
      // The orbit keeps its own distance and pitch: its overview.
      vec3.set(to.target, from.position[0], from.position[1] - from.eyeHeight, from.position[2]);
      to.yaw = from.yaw;
      to.keepAboveGround(Math.max(this.world.spacing * 0.05, 0.01 * to.distance));
    } else if (mode === 'orbit') {
      // Orbit around the ground point ahead, from where the eye is.
      const ahead = this.groundAhead(from);
      to.lookAround(ahead[0], ahead[1], ahead[2], from.position);
    } else if (mode === 'walk' && clearanceOf(from.position, this.world) > WALK_FROM_ABOVE * to.eyeHeight) {
      const ahead = this.groundAhead(from);
      to.copyPose(from);
      to.standAt(ahead[0], ahead[2]);
    } else {
      to.copyPose(from);
    }
    this.active = to;
    this.changed();
  }

  /** Where the view direction meets the ground, or a point ahead at the current clearance. */
  groundAhead(camera) {
    const [ex, ey, ez] = camera.position;
    const d = [camera.target[0] - ex, camera.target[1] - ey, camera.target[2] - ez];
    const length = Math.hypot(...d);
    const reach = Math.hypot(this.world.extentX, this.world.extentZ, this.world.high - this.world.low);
    const step = Math.max(this.world.spacing, reach / 4000);
    for (let t = step; t < reach * 2; t += step) {
      const x = ex + (d[0] / length) * t, y = ey + (d[1] / length) * t, z = ez + (d[2] / length) * t;
      if (y <= this.world.ground(x, z)) return [x, y, z];
    }
    return [ex + d[0], ey + d[1], ez + d[2]];
  }

  changed() {
    this.onChange();
  }

  /**
   * Flies the orbit camera to look at `to.target` from `to.position` in `seconds` (0: at once).
   * @returns {Promise<boolean>} whether it arrived (false: stopped by another flight, a drag or the keys)
   */
  flyTo(to, seconds) {
    this.flight?.stop();
    if (this.active.mode !== 'orbit') this.setMode('orbit');
    this.flight = new CameraFlight(this.cameras.orbit, to, seconds);
    const { finished } = this.flight;
    if (seconds === 0) this.step(0);
    this.changed();
    return finished;
  }

  /** Ends a flight where it is: the person took the camera. */
  stopFlight() {
    this.flight?.stop();
    this.flight = null;
  }

  /** Moves the fly or walk camera along a followed track or for the held keys; true while it moves. */
  step(seconds) {
    if (this.flight) {
      if (!this.flight.step(Math.min(seconds, 0.1))) this.flight = null;
      return true; // this frame moved the camera
    }
    if (this.follow && this.active.mode !== 'orbit') {
      this.follow.step(Math.min(seconds, 0.1), this.active, this.verticalScale);
      if (this.follow.playing) return true;
    }
    if (this.held.size === 0) return false;
    this.move.forward = this.move.right = this.move.up = 0;
    this.held.forEach(this.addMove);
    const dt = Math.min(seconds, 0.1);
    if (this.active.mode === 'orbit') this.orbitByKeys(dt);
    else this.active.move(dt, this.move, this.fast);
    return true;
  }

  /**
   * The orbit camera by the keys, for those who use no pointer: left and right turn around the
   * target, up and down come closer and go back, Q and E lower and raise the view; with shift,
   * left, right, up and down move the target over the ground.
   */
  orbitByKeys(dt) {
    const orbit = this.active, { forward, right, up } = this.move;
    if (this.fast) orbit.drag(-right * dt * 400, -forward * dt * 400, true);
    else {
      orbit.drag(right * dt * ORBIT_KEY_TURN, -up * dt * ORBIT_KEY_TURN * 0.6, false);
      orbit.zoom(Math.exp(-forward * dt * 1.2));
    }
  }

  /** Mouse, wheel and touch on `element`, keys where the viewer takes them (viewer_dom.js). */
  attach(element, dom) {
    let drag = null;
    element.addEventListener('pointerdown', (e) => {
      if (e.pointerType === 'touch') return;
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
      this.stopFlight();
      try { element.setPointerCapture(e.pointerId); } catch { /* a synthetic or finished pointer */ }
    });
    element.addEventListener('pointermove', (e) => {
      if (!drag || e.pointerType === 'touch') return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX;
      drag.y = e.clientY;
      if (this.active.mode === 'orbit') this.active.drag(dx, dy, drag.pan);
      else this.active.look(dx, dy);
      this.changed();
    });
    const end = () => { drag = null; };
    element.addEventListener('pointerup', end);
    element.addEventListener('pointercancel', end);
    element.addEventListener('contextmenu', (e) => e.preventDefault());
    element.addEventListener('wheel', (e) => {
      e.preventDefault();
      if (this.active.mode === 'orbit') this.active.zoom(Math.exp(e.deltaY * 0.001));
      else this.active.move(0.05 * Math.sign(-e.deltaY), { forward: 1, right: 0, up: 0 }, e.shiftKey);
      this.changed();
    }, { passive: false });
    dom.on(dom.keyTarget, 'keydown', (e) => {
      this.fast = e.shiftKey;
      if (!MOVE_KEYS[e.code] || isTyping(e)) return;
      e.preventDefault();
      this.held.add(e.code);
      this.changed();
    });
    dom.on(dom.keyTarget, 'keyup', (e) => {
      this.fast = e.shiftKey;
      this.held.delete(e.code);
    });
    dom.on(window, 'blur', () => this.held.clear());
    if (!dom.page) dom.on(dom.keyTarget, 'focusout', () => this.held.clear()); // keys released elsewhere never reach it
    attachTouchControls(element, this);
  }
}

/** A key typed into a form field is not a camera key. */
export function isTyping(e) {
  return /^(INPUT|SELECT|TEXTAREA)$/.test(e.target?.tagName ?? '');
}
