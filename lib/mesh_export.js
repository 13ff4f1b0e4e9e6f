// The hexagon mesh as plain triangles for other programs: decodes the core's fan stream,
// clips the triangles to the data rectangle (the lattice reaches past the field on the east,
// west and south, docs/DESIGN.md) and streams a Wavefront OBJ file.
//
// Frame: x east from the first column, y up, z south from the first row, all in metres. A
// triangle (a, b, c) is counter-clockwise seen from +y when (b - a) x (c - a) has a positive
// y component, i.e. (b.z - a.z) * (c.x - a.x) - (b.x - a.x) * (c.z - a.z) > 0.
import { openSync, writeSync, closeSync } from 'node:fs';
import { RESTART_INDEX } from '../web/core/core.js';

/** Twice the area of (a, b, c) in the x-z plane, positive when counter-clockwise seen from +y. */
export function ccwArea2(ax, az, bx, bz, cx, cz) {
  return (bz - az) * (cx - ax) - (bx - ax) * (cz - az);
}

/**
 * Decodes a fan stream: each fan `a b c d ...` closed by 0xFFFFFFFF is the triangles (a, b, c),
 * (a, c, d), ... Fans are counted by length: 8 indices = full hexagon (centre and 7 corners,
 * the first repeated), 5 = boundary semi-hexagon (centre and 4 corners), 4 = interior
 * semi-hexagon; any other length is counted under `other`.
 * @param {Uint32Array} indices the fan indices (copied: the view may be detached later)
 * @returns {{triangles: Uint32Array, fans: {full: number, boundarySemi: number, interiorSemi: number, other: number, total: number}}}
 */
export function decodeFans(indices) {
  let triangleCount = 0;
  let length = 0;
  const fans = { full: 0, boundarySemi: 0, interiorSemi: 0, other: 0, total: 0 };
  for (let i = 0; i < indices.length; i++) {
    if (indices[i] !== RESTART_INDEX) {
      length += 1;
      continue;
    }
    if (length >= 3) triangleCount += length - 2;
    if (length === 8) fans.full += 1;
    else if (length === 5) fans.boundarySemi += 1;
    else if (length === 4) fans.interiorSemi += 1;
    else fans.other += 1;
    fans.total += 1;
    length = 0;
  }
  const triangles = new Uint32Array(triangleCount * 3);
  let t = 0, start = 0;
  for (let i = 0; i <= indices.length; i++) {
    if (i < indices.length && indices[i] !== RESTART_INDEX) continue;
    for (let k = start + 1; k + 1 < i; k++) {
      triangles[t++] = indices[start];
      triangles[t++] = indices[k];
      triangles[t++] = indices[k + 1];
    }
    start = i + 1;
  }
  return { triangles, fans };
}

/**
 * Removes triangles without area (the exact-sample embedding has some: three vertices on one
 * column where a coarser cell meets finer ones) without opening the mesh: the middle vertex of
 * such a triangle is inserted into the triangle across its long edge, which is fanned again.
 * A zero-area triangle whose long edge has no usable neighbour is dropped.
 * @param {Float32Array|Float64Array} positions x, y, z first of every `stride` floats
 * @param {number} stride
 * @param {Uint32Array} triangles counter-clockwise seen from +y
 * @returns {{triangles: Uint32Array, degenerate: number, unresolved: number}} the same array
 *   when no triangle is degenerate
 */
export function resolveDegenerate(positions, stride, triangles) {
  const X = (v) => positions[v * stride], Z = (v) => positions[v * stride + 2];
  const isFlat = (a, b, c) => {
    const area = ccwArea2(X(a), Z(a), X(b), Z(b), X(c), Z(c));
    const scale = Math.max(Math.abs(X(b) - X(a)), Math.abs(Z(b) - Z(a)), Math.abs(X(c) - X(a)), Math.abs(Z(c) - Z(a)));
    return Math.abs(area) <= 1e-9 * scale * scale;
  };
  const flat = [];
  for (let t = 0; t < triangles.length; t += 3) {
    if (isFlat(triangles[t], triangles[t + 1], triangles[t + 2])) flat.push(t);
  }
  if (flat.length === 0) return { triangles, degenerate: 0, unresolved: 0 };

  // For each flat triangle: its middle vertex and the directed long edge p -> q; the triangle
  // across that edge holds q -> p.
  const vertexCount = Math.floor(positions.length / stride);
  const wanted = new Map(); // q * vertexCount + p -> middle vertices (on p-q)
  const marked = new Uint8Array(vertexCount);
  const skip = new Set(flat);
  const length2 = (u, v) => (X(u) - X(v)) ** 2 + (Z(u) - Z(v)) ** 2;
  for (const t of flat) {
    const v = [triangles[t], triangles[t + 1], triangles[t + 2]];
    let long = 0;
    for (let k = 1; k < 3; k++) if (length2(v[k], v[(k + 1) % 3]) > length2(v[long], v[(long + 1) % 3])) long = k;
    const p = v[long], q = v[(long + 1) % 3], middle = v[(long + 2) % 3];
    if (length2(p, middle) === 0 || length2(q, middle) === 0) continue; // coincident points: drop
    const key = q * vertexCount + p;
    if (!wanted.has(key)) wanted.set(key, []);
    wanted.get(key).push(middle);
    marked[q] = 1;
  }
  // The triangles across those edges, with the points to insert on each of their edges.
  const inserts = new Map(); // triangle offset -> [[points on edge 0], [edge 1], [edge 2]]
  let resolved = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    if (skip.has(t)) continue;
    for (let k = 0; k < 3; k++) {
      const from = triangles[t + k], to = triangles[t + (k + 1) % 3];
      if (!marked[from]) continue;
      const middles = wanted.get(from * vertexCount + to);
      if (!middles) continue;
      if (!inserts.has(t)) inserts.set(t, [[], [], []]);
      inserts.get(t)[k].push(...middles);
      resolved += middles.length;
    }
  }
  const out = new Growable(Uint32Array, triangles.length + 6 * inserts.size);
  for (let t = 0; t < triangles.length; t += 3) {
    if (skip.has(t)) continue;
    const edges = inserts.get(t);
    if (!edges) {
      out.push3(triangles[t], triangles[t + 1], triangles[t + 2]);
      continue;
    }
    const points = [];
    for (let k = 0; k < 3; k++) {
      const from = triangles[t + k];
      points.push({ v: from, x: X(from), z: Z(from) });
      const along = edges[k].slice().sort((a, b) => length2(from, a) - length2(from, b));
      for (const v of along) points.push({ v, x: X(v), z: Z(v) });
    }
    fanPolygon(points, (p, q, r) => out.push3(p.v, q.v, r.v));
  }
  return { triangles: out.array, degenerate: flat.length, unresolved: flat.length - resolved };
}

/** A growable typed array. */
class Growable {
  constructor(ArrayType, capacity) {
    this.ArrayType = ArrayType;
    this.data = new ArrayType(Math.max(16, capacity));
    this.length = 0;
  }

  push3(a, b, c) {
    if (this.length + 3 > this.data.length) {
      const bigger = new this.ArrayType(this.data.length * 2);
      bigger.set(this.data);
      this.data = bigger;
    }
    this.data[this.length] = a;
    this.data[this.length + 1] = b;
    this.data[this.length + 2] = c;
    this.length += 3;
  }

  get array() {
    return this.data.subarray(0, this.length);
  }
}

// The four clip lines: x >= 0, x <= xMax, z >= 0, z <= zMax.
const LINES = 4;
const signedDistance = (line, x, z, xMax, zMax) =>
  line === 0 ? x : line === 1 ? xMax - x : line === 2 ? z : zMax - z;

/**
 * Clips triangles to the rectangle [0, xMax] x [0, zMax] of the x-z plane (Sutherland-Hodgman
 * on its four half-planes, heights interpolated linearly), fans each clipped polygon again and
 * keeps only vertices that are used. Clipped vertices on an edge shared by two triangles are
 * computed once from that edge and shared, so a watertight mesh stays watertight. Vertices
 * within a millionth of the rectangle's size outside it count as on its outline and are moved
 * onto it.
 * @param {Float32Array|Float64Array} positions vertex positions, x, y, z first of every `stride` floats
 * @param {number} stride floats per vertex
 * @param {Uint32Array} triangles 3 indices per triangle, counter-clockwise seen from +y
 * @param {number} xMax east edge of the rectangle in metres ((W - 1) * spacing x)
 * @param {number} zMax south edge in metres ((H - 1) * spacing y)
 * @returns {{vertices: Float64Array, faces: Uint32Array, inside: number, clipped: number, dropped: number}}
 *   vertices x, y, z per used vertex; faces 3 zero-based indices each, counter-clockwise;
 *   inside/clipped/dropped count the input triangles kept whole, cut, and dropped
 */
export function clipToRectangle(positions, stride, triangles, xMax, zMax) {
  const vertexCount = Math.floor(positions.length / stride);
  const eps = 1e-6 * Math.max(xMax, zMax, 1);
  const snap = (v, max) => (v < eps && v > -eps ? 0 : v > max - eps && v < max + eps ? max : v);

  // Per vertex: bit k set when it lies outside clip line k by more than eps.
  const outside = new Uint8Array(vertexCount);
  for (let v = 0; v < vertexCount; v++) {
    const x = positions[v * stride], z = positions[v * stride + 2];
    let mask = 0;
    for (let line = 0; line < LINES; line++) if (signedDistance(line, x, z, xMax, zMax) < -eps) mask |= 1 << line;
    outside[v] = mask;
  }

  const remap = new Int32Array(vertexCount).fill(-1);
  const out = new Growable(Float64Array, 3 * vertexCount);
  const faces = new Growable(Uint32Array, triangles.length);
  const newVertices = new Map(); // "x|z" of a vertex made by clipping -> output index

  const useOriginal = (v) => {
    if (remap[v] < 0) {
      remap[v] = out.length / 3;
      out.push3(snap(positions[v * stride], xMax), positions[v * stride + 1], snap(positions[v * stride + 2], zMax));
    }
    return remap[v];
  };
  const useNew = (key, x, y, z) => {
    let index = newVertices.get(key);
    if (index === undefined) {
      index = out.length / 3;
      out.push3(x, y, z);
      newVertices.set(key, index);
    }
    return index;
  };
  const use = (p) => (p.kind === 'v' ? useOriginal(p.a) : useNew(p.key, p.x, p.y, p.z));

  // A clipped polygon's vertex: an original vertex (kind 'v', a), a point where an original
  // edge (a < b) crosses clip line `line` (kind 'e'), or a corner of the rectangle where clip
  // lines `line` and `line2` meet (kind 'c').
  const original = (a) => ({ kind: 'v', a, b: -1, line: -1, line2: -1,
    x: positions[a * stride], y: positions[a * stride + 1], z: positions[a * stride + 2] });
  const sharedEdge = (p, q) => {
    if (p.kind === 'v' && q.kind === 'v') return [Math.min(p.a, q.a), Math.max(p.a, q.a)];
    if (p.kind === 'c' || q.kind === 'c') return null;
    if (p.kind === 'e' && q.kind === 'e') return p.a === q.a && p.b === q.b ? [p.a, p.b] : null;
    const [v, e] = p.kind === 'v' ? [p, q] : [q, p];
    return v.a === e.a || v.a === e.b ? [e.a, e.b] : null;
  };
  const linesOf = (p) => {
    if (p.kind === 'e') return [p.line];
    if (p.kind === 'c') return [p.line, p.line2];
    const lines = [];
    for (let line = 0; line < LINES; line++) {
      if (Math.abs(signedDistance(line, p.x, p.z, xMax, zMax)) <= eps) lines.push(line);
    }
    return lines;
  };
  const cornerX = (line, other) => (line === 0 || other === 0 ? 0 : xMax);
  const cornerZ = (line, other) => (line === 2 || other === 2 ? 0 : zMax);

  // The point where segment p-q (p strictly inside line, q strictly outside, or the reverse)
  // crosses `line`, computed from the original edge it lies on when there is one, so both
  // triangles of that edge get the same numbers.
  const crossing = (p, q, line) => {
    const edge = sharedEdge(p, q);
    if (edge) {
      const [a, b] = edge;
      const ax = positions[a * stride], ay = positions[a * stride + 1], az = positions[a * stride + 2];
      const bx = positions[b * stride], by = positions[b * stride + 1], bz = positions[b * stride + 2];
      const da = signedDistance(line, ax, az, xMax, zMax), db = signedDistance(line, bx, bz, xMax, zMax);
      const t = da / (da - db);
      let x = ax + t * (bx - ax), z = az + t * (bz - az);
      if (line < 2) x = line === 0 ? 0 : xMax;
      else z = line === 2 ? 0 : zMax;
      return { kind: 'e', a, b, line, line2: -1, x, y: ay + t * (by - ay), z };
    }
    // Otherwise p-q runs along an earlier clip line: it crosses `line` at a corner.
    const dp = signedDistance(line, p.x, p.z, xMax, zMax), dq = signedDistance(line, q.x, q.z, xMax, zMax);
    const t = dp / (dp - dq);
    const y = p.y + t * (q.y - p.y);
    const common = linesOf(p).find((l) => l !== line && (l >> 1) !== (line >> 1) && linesOf(q).includes(l));
    if (common !== undefined) {
      return { kind: 'c', a: -1, b: -1, line, line2: common, x: cornerX(line, common), y, z: cornerZ(line, common) };
    }
    // Not expected; keep the plain intersection.
    return { kind: 'c', a: -1, b: -1, line, line2: -1, x: p.x + t * (q.x - p.x), y, z: p.z + t * (q.z - p.z) };
  };

  let inside = 0, clipped = 0, dropped = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    const oa = outside[a], ob = outside[b], oc = outside[c];
    if ((oa | ob | oc) === 0) {
      inside += 1;
      faces.push3(useOriginal(a), useOriginal(b), useOriginal(c));
      continue;
    }
    if ((oa & ob & oc) !== 0) {
      dropped += 1;
      continue;
    }
    let polygon = [original(a), original(b), original(c)];
    for (let line = 0; line < LINES && polygon.length >= 3; line++) {
      const result = [];
      for (let i = 0; i < polygon.length; i++) {
        const p = polygon[i], q = polygon[(i + 1) % polygon.length];
        const dp = signedDistance(line, p.x, p.z, xMax, zMax), dq = signedDistance(line, q.x, q.z, xMax, zMax);
        if (dp >= -eps) result.push(p);
        // A crossing only between a point strictly inside and one strictly outside.
        if ((dp > eps && dq < -eps) || (dp < -eps && dq > eps)) result.push(crossing(p, q, line));
      }
      polygon = result;
    }
    // Vertices made by clipping are named by their position on the outline, original ones by
    // their index; points that coincide are merged before the polygon is fanned again.
    const points = [];
    for (const p of polygon) {
      if (p.kind === 'v') {
        p.key = p.a;
        p.x = snap(p.x, xMax);
        p.z = snap(p.z, zMax);
      } else {
        p.x = snap(p.x, xMax);
        p.z = snap(p.z, zMax);
        p.key = `${p.x}|${p.z}`;
      }
      if (points.length === 0 || points[points.length - 1].key !== p.key) points.push(p);
    }
    while (points.length > 1 && points[0].key === points[points.length - 1].key) points.pop();
    const before = faces.length;
    fanPolygon(points, (p, q, r) => faces.push3(use(p), use(q), use(r)));
    if (faces.length === before) dropped += 1;
    else clipped += 1;
  }
  return { vertices: out.array, faces: faces.array, inside, clipped, dropped };
}

/**
 * Triangulates a convex polygon of points {x, z} (counter-clockwise seen from +y) as a fan from
 * the corner that makes the fattest thinnest triangle, so collinear points on its outline give
 * no empty triangle; emit(p, q, r) gets every triangle with area, counter-clockwise.
 */
export function fanPolygon(points, emit) {
  const n = points.length;
  if (n < 3) return;
  const area = (i, j, k) => {
    const p = points[i], q = points[j], r = points[k];
    return ccwArea2(p.x, p.z, q.x, q.z, r.x, r.z);
  };
  let apex = 0;
  if (n > 3) {
    let best = -Infinity;
    for (let k = 0; k < n; k++) {
      let thinnest = Infinity;
      for (let i = 1; i + 1 < n; i++) thinnest = Math.min(thinnest, area(k, (k + i) % n, (k + i + 1) % n));
      if (thinnest > best) {
        best = thinnest;
        apex = k;
      }
    }
  }
  for (let i = 1; i + 1 < n; i++) {
    const j = (apex + i) % n, k = (apex + i + 1) % n;
    if (area(apex, j, k) > 0) emit(points[apex], points[j], points[k]);
  }
}

/**
 * Writes vertices and faces as a Wavefront OBJ file, in chunks (meshes of millions of
 * triangles never become one string). Coordinates are rounded to 0.1 mm, never past the
 * rectangle [0, xMax] x [0, zMax] (none for vertices in another frame: xMax and zMax null).
 * @param {string} path
 * @param {{vertices: Float64Array, faces: Uint32Array}} mesh zero-based faces
 * @param {string[]} comments header lines (without '#')
 * @param {number|null} xMax
 * @param {number|null} zMax
 * @param {{uv: Float64Array, mtllib: string, material: string}|null} [texture] a texture
 *   coordinate (u, v) per vertex, the material file's name beside the OBJ and the material's
 *   name: faces then name each vertex's texture coordinate too (`f v/vt ...`)
 */
export function writeObj(path, { vertices, faces }, comments, xMax, zMax, texture = null) {
  const fd = openSync(path, 'w');
  try {
    const CHUNK = 1 << 20;
    let text = comments.map((line) => `# ${line}\n`).join('');
    if (texture) text += `mtllib ${texture.mtllib}\n`;
    const flush = (force) => {
      if (text.length >= CHUNK || (force && text.length > 0)) {
        writeSync(fd, text);
        text = '';
      }
    };
    const q = 1e4;
    // The data rectangle bounds x and z, unless the vertices are in another frame (xMax null).
    const xLimit = xMax === null ? Infinity : Math.floor(xMax * q) / q, zLimit = zMax === null ? Infinity : Math.floor(zMax * q) / q;
    const xFloor = xMax === null ? -Infinity : 0, zFloor = zMax === null ? -Infinity : 0;
    const round = (v) => Math.round(v * q) / q;
    for (let i = 0; i < vertices.length; i += 3) {
      const x = Math.max(xFloor, Math.min(xLimit, round(vertices[i])));
      const z = Math.max(zFloor, Math.min(zLimit, round(vertices[i + 2])));
      text += `v ${x} ${round(vertices[i + 1])} ${z}\n`;
      flush(false);
    }
    if (texture) {
      // 1e-7 of the image: a hundredth of a pixel of an image 100 000 pixels across.
      const t = 1e7;
      for (let i = 0; i < texture.uv.length; i += 2) {
        text += `vt ${Math.round(texture.uv[i] * t) / t} ${Math.round(texture.uv[i + 1] * t) / t}\n`;
        flush(false);
      }
      text += `usemtl ${texture.material}\n`;
    }
    for (let i = 0; i < faces.length; i += 3) {
      const a = faces[i] + 1, b = faces[i + 1] + 1, c = faces[i + 2] + 1;
      text += texture ? `f ${a}/${a} ${b}/${b} ${c}/${c}\n` : `f ${a} ${b} ${c}\n`;
      flush(false);
    }
    flush(true);
  } finally {
    closeSync(fd);
  }
}
