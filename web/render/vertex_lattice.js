// Every vertex's lattice point as two integers (half columns east, rows south), beside the
// core's vertex pool on the GPU: the terrain's vertex shader places vertices from them, exact at
// any distance from the field's first sample (shading/eye_anchor.js). The core's float
// positions are lattice points, x = half columns times half the spacing and z = rows times the
// spacing, and a double brings the integers back exactly (as HexMesh::latticeAt does) for fields
// of up to 2^22 samples a side. Worked out here for the vertices the core marked dirty, in an
// array that grows by doubling: the frame path makes nothing new.
import { STREAM_VERTEX_BYTES } from '../core/core.js';

const VERTEX_WORDS = STREAM_VERTEX_BYTES / 4;
export const LATTICE_BYTES = 8; // two int32 per vertex

export class VertexLattice {
  constructor(gl) {
    this.gl = gl;
    this.points = new Int32Array(0);
    this.halfColumnsPerMetre = 2;
    this.rowsPerMetre = 1;
    this.createGlObjects();
  }

  /** The GL buffer, made again after a lost context (the next update fills all of it). */
  createGlObjects() {
    this.buffer = this.gl.createBuffer();
    this.capacity = 0; // vertices allocated on the GPU
  }

  /** The field's sample spacing, metres. */
  setSpacing(spacingX, spacingY) {
    this.halfColumnsPerMetre = 2 / spacingX;
    this.rowsPerMetre = 1 / spacingY;
  }

  /**
   * Brings the lattice points of `vertexCount` vertices of the pool (all of WASM memory as
   * `f32`, the pool at byte `pointer`) up to date where the ranges say the pool changed (`pairs`
   * [first, count] pairs at int32 index `rangesAt` of `i32`), or everywhere when `all`, on the
   * GPU too. Returns the bytes uploaded.
   */
  update(f32, pointer, vertexCount, i32, rangesAt, pairs, all) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    if (vertexCount > this.capacity) {
      this.capacity = Math.max(vertexCount, 2 * this.capacity, 1 << 13);
      const grown = new Int32Array(2 * this.capacity);
      grown.set(this.points.subarray(0, Math.min(this.points.length, grown.length)));
      this.points = grown;
      gl.bufferData(gl.ARRAY_BUFFER, this.points.byteLength, gl.DYNAMIC_DRAW);
      all = true;
    }
    const base = pointer / 4;
    if (all) {
      this.convert(f32, base, 0, vertexCount);
      if (vertexCount > 0) gl.bufferSubData(gl.ARRAY_BUFFER, 0, this.points, 0, 2 * vertexCount);
      return vertexCount * LATTICE_BYTES;
    }
    let uploaded = 0;
    for (let k = 0; k < pairs; k++) {
      const first = i32[rangesAt + 2 * k], count = i32[rangesAt + 2 * k + 1];
      this.convert(f32, base, first, count);
      gl.bufferSubData(gl.ARRAY_BUFFER, first * LATTICE_BYTES, this.points, 2 * first, 2 * count);
      uploaded += count * LATTICE_BYTES;
    }
    return uploaded;
  }

  // The lattice points of vertices [first, first + count) from their float positions.
  convert(f32, base, first, count) {
    const points = this.points, columns = this.halfColumnsPerMetre, rows = this.rowsPerMetre;
    for (let v = first, end = first + count; v < end; v++) {
      const at = base + v * VERTEX_WORDS;
      points[2 * v] = Math.round(f32[at] * columns);
      points[2 * v + 1] = Math.round(f32[at + 2] * rows);
    }
  }
}
