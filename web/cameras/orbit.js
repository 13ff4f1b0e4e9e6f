// Orbit camera: looks at a target point from a distance, yaw and pitch. Matrices come from
// gl-matrix; scratch objects are reused so a frame allocates nothing.
import { mat4, vec3 } from 'gl-matrix';

export class OrbitCamera {
  constructor() {
    this.target = vec3.create(); // metres
    this.distance = 1000;        // metres from the target
    this.yaw = 0;                // radians, 0 looks north (towards -z)
    this.pitch = 0.5;            // radians above the horizon
    this.fovY = (50 * Math.PI) / 180;
    this.position = vec3.create();
    this.view = mat4.create();
    this.projection = mat4.create();
    this.viewProjection = mat4.create();
    this.up = vec3.fromValues(0, 1, 0);
  }

  /**
   * Looks at a point of interest (metres) from the south, low enough to see relief, far
   * enough to see a region `extent` metres across.
   */
  frame(focusX, focusY, focusZ, extent) {
    vec3.set(this.target, focusX, focusY, focusZ);
    this.distance = 0.3 * extent;
    this.yaw = -0.25;
    this.pitch = 0.38;
  }

  /** Recomputes the matrices for a viewport aspect ratio (width / height). */
  update(aspect) {
    const cp = Math.cos(this.pitch);
    vec3.set(this.position,
      this.target[0] + this.distance * cp * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * cp * Math.cos(this.yaw));
    mat4.lookAt(this.view, this.position, this.target, this.up);
    // Near and far follow the distance so both a small tile and a continent keep depth precision.
    this.near = Math.max(0.5, this.distance * 0.002);
    this.far = this.distance * 20;
    this.aspect = aspect;
    mat4.perspective(this.projection, this.fovY, aspect, this.near, this.far);
    mat4.multiply(this.viewProjection, this.projection, this.view);
  }
}

/** Mouse/touch orbiting (drag), panning (right or shift drag) and zoom (wheel) on an element. */
export function attachOrbitControls(element, camera, onChange) {
  let last = null;
  element.addEventListener('pointerdown', (e) => {
    last = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
    element.setPointerCapture(e.pointerId);
  });
  element.addEventListener('pointermove', (e) => {
    if (!last) return;
    const dx = e.clientX - last.x, dy = e.clientY - last.y;
    last.x = e.clientX;
    last.y = e.clientY;
    if (last.pan) {
      const s = camera.distance * 0.0015;
      const c = Math.cos(camera.yaw), n = Math.sin(camera.yaw);
      camera.target[0] -= (dx * c - dy * n) * s;
      camera.target[2] -= (dx * n + dy * c) * s;
    } else {
      camera.yaw -= dx * 0.005;
      camera.pitch = Math.min(1.55, Math.max(0.02, camera.pitch + dy * 0.005));
    }
    onChange();
  });
  const end = () => { last = null; };
  element.addEventListener('pointerup', end);
  element.addEventListener('pointercancel', end);
  element.addEventListener('contextmenu', (e) => e.preventDefault());
  element.addEventListener('wheel', (e) => {
    e.preventDefault();
    camera.distance *= Math.exp(e.deltaY * 0.001);
    onChange();
  }, { passive: false });
}
