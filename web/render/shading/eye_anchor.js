// The terrain drawn relative to the eye (shaders/terrain.vert). A float keeps 24 bits: a vertex
// 40,000 km east of a world field's first sample is known to 4 m, and a drawn frame 6,000 km
// from the eye puts half-metre steps into the view matrix, enough for a valley floor seen from
// 2 m to shake. So the vertex shader takes each vertex's exact lattice point (vertex_lattice.js)
// and an anchor: a lattice point under the eye. From the integers' difference it finds the
// vertex's flat offset from the anchor, draws it in the anchor's tangent frame (earth.glsl
// earthOffset), turns it into the drawn frame with the anchor's axes, and adds the anchor's place
// relative to the eye, which this file works out in doubles. The view-projection is the camera's
// without its translation. Near the eye every number the GPU sees is small.
//
// The sphere that projected grids are wrapped on keeps distances and directions from the
// field's centre only, so its anchor stays there (its offsets are still exact; its drawn
// points are as precise as floats are at their distance from the centre).
import { mat4 } from 'gl-matrix';
import { EARTH_SPHERE, drawnAxes, drawnPoint } from '../../geo/index.js';

export const ANCHOR_UNIFORMS = ['uAnchorLattice', 'uAnchorRest', 'uLatticeMetres', 'uLatticeLast', 'uAnchorLatitude',
  'uAnchorAxes', 'uAnchorFromEye', 'uViewProjectionFromEye'];

export class EyeAnchor {
  constructor() {
    this.spacingX = 1;
    this.spacingY = 1;
    // Typed arrays made once: a frame hands the GPU only these.
    this.anchorLattice = new Int32Array(2);
    this.rest = new Float32Array(2);
    this.latticeMetres = new Float32Array([0.5, 1]);
    this.latticeLast = new Int32Array(2);
    this.axes = new Float64Array(9);
    this.axes32 = new Float32Array(9);
    this.anchorPoint = new Float64Array(3);
    this.fromEye = new Float32Array(3);
    this.rotation = mat4.create();
    this.viewProjection = mat4.create();
  }

  /** The field's lattice: sample spacing (metres) and size (samples). */
  setLattice(spacingX, spacingY, width, height) {
    this.spacingX = spacingX;
    this.spacingY = spacingY;
    this.latticeMetres[0] = 0.5 * spacingX, this.latticeMetres[1] = spacingY;
    this.latticeLast[0] = 2 * (width - 1), this.latticeLast[1] = height - 1;
  }

  /**
   * Sets the uniforms for `camera` (placed on `earth` by web/cameras/on_the_earth.js: its flat
   * position and its drawn one) in the program in use.
   */
  apply(gl, u, camera, earth) {
    const halfColumn = 0.5 * this.spacingX, row = this.spacingY;
    // The anchor: the lattice point under the eye, or the sphere's centre.
    const sphere = earth.kind === EARTH_SPHERE;
    const x = sphere ? earth.originX : camera.position[0], z = sphere ? earth.originZ : camera.position[2];
    // On the field (a far eye sees it all from afar: any point of it will do).
    const columnAt = Math.min(Math.max(Math.round(x / halfColumn), 0), this.latticeLast[0]);
    const rowAt = Math.min(Math.max(Math.round(z / row), 0), this.latticeLast[1]);
    this.anchorLattice[0] = columnAt, this.anchorLattice[1] = rowAt;
    const anchorX = sphere ? x : columnAt * halfColumn, anchorZ = sphere ? z : rowAt * row;
    this.rest[0] = anchorX - columnAt * halfColumn, this.rest[1] = anchorZ - rowAt * row;
    drawnAxes(earth, anchorX, anchorZ, this.axes);
    this.axes32.set(this.axes);
    drawnPoint(earth, anchorX, 0, anchorZ, this.anchorPoint);
    const eye = camera.drawnPosition ?? camera.position;
    for (let k = 0; k < 3; k++) this.fromEye[k] = this.anchorPoint[k] - eye[k];
    // The camera's view turned only: the eye at the origin.
    const r = mat4.copy(this.rotation, camera.view);
    r[12] = r[13] = r[14] = 0;
    mat4.multiply(this.viewProjection, camera.projection, r);
    gl.uniform2iv(u.uAnchorLattice, this.anchorLattice);
    gl.uniform2fv(u.uAnchorRest, this.rest);
    gl.uniform2fv(u.uLatticeMetres, this.latticeMetres);
    gl.uniform2iv(u.uLatticeLast, this.latticeLast);
    gl.uniform1f(u.uAnchorLatitude, earth.latitude0 - (anchorZ - earth.originZ) / earth.metresPerRadianZ);
    gl.uniformMatrix3fv(u.uAnchorAxes, false, this.axes32);
    gl.uniform3fv(u.uAnchorFromEye, this.fromEye);
    gl.uniformMatrix4fv(u.uViewProjectionFromEye, false, this.viewProjection);
  }
}
