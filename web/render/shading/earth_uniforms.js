// The curved Earth's uniforms (shaders/earth.glsl) and the eye, for every program that draws on
// the terrain: the terrain, the sky, and the lines and overlays on the ground. Converted once per
// shape, so a frame hands the GPU only typed arrays made here.
import { FLAT_EARTH } from '../../geo/index.js';

export const EARTH_UNIFORMS = ['uEarthKind', 'uEarthOrigin', 'uEarthRadius', 'uEarthGeographic', 'uEyeHeight', 'uEyeUp', 'uCameraPosition'];

export class EarthUniforms {
  constructor() {
    this.earth = FLAT_EARTH;
    this.origin = new Float32Array(2);
    this.geographic = new Float32Array(3);
    this.eye = new Float32Array(3);
    this.eyeUp = new Float32Array([0, 1, 0]);
    this.set(FLAT_EARTH);
  }

  /** The shape the next frames are drawn on (web/geo/earth_shape.js). */
  set(earth) {
    this.earth = earth;
    this.origin[0] = earth.originX, this.origin[1] = earth.originZ;
    this.geographic[0] = earth.latitude0, this.geographic[1] = earth.metresPerRadianX, this.geographic[2] = earth.metresPerRadianZ;
  }

  /**
   * Sets the shape and the camera's eye (where it is drawn, on_the_earth.js; its flat height
   * over the exaggeration is its true height) in the program in use.
   */
  apply(gl, u, camera, verticalScale) {
    const e = this.earth, drawn = camera.drawnPosition ?? camera.position;
    this.eye[0] = drawn[0], this.eye[1] = drawn[1], this.eye[2] = drawn[2];
    gl.uniform1i(u.uEarthKind, e.kind);
    gl.uniform2fv(u.uEarthOrigin, this.origin);
    gl.uniform1f(u.uEarthRadius, e.radius);
    gl.uniform3fv(u.uEarthGeographic, this.geographic);
    gl.uniform1f(u.uEyeHeight, camera.position[1] / verticalScale);
    gl.uniform3fv(u.uCameraPosition, this.eye);
    const up = camera.drawnUp ?? camera.up;
    this.eyeUp[0] = up[0], this.eyeUp[1] = up[1], this.eyeUp[2] = up[2];
    gl.uniform3fv(u.uEyeUp, this.eyeUp);
  }
}
