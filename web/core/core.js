// The one JS module that owns the WebAssembly core (src/api/hexlod.h is the ABI it wraps; the
// diagnostics of src/api/hexlod_diagnostics.h exist only in the diagnostics build that Node
// loads, see bin/node_core.js). It runs unchanged in the browser, in workers and in Node; only
// how the .wasm bytes are found differs (the browser fetches them next to this module, Node
// passes `wasmBinary`).
//
// WASM memory may grow during any core call, which detaches every typed-array view on the old
// buffer: views are re-made whenever `view.buffer !== memory.buffer`, and the views handed to
// callers (stream(), levelView(), samples()) are valid only until the next core call.
import createHexlodCore from '../../build/wasm/hexlod_core.mjs';

/** Sample type names of the loaders mapped to HEXLOD_SAMPLE_* and typed-array constructors. */
export const SAMPLE_TYPES = {
  u8: { code: 1, Array: Uint8Array },
  u16: { code: 2, Array: Uint16Array },
  i16: { code: 3, Array: Int16Array },
  f32: { code: 4, Array: Float32Array },
};

/** Index layouts of the fan stream (HEXLOD_LAYOUT_*). */
export const STREAM_LAYOUTS = { fans: 0, triangles: 1 };
/** Lattice embeddings (HEXLOD_EMBEDDING_*). */
export const EMBEDDINGS = { exact: 0, shifted: 1 };
/**
 * A stream vertex (src/mesh/stream_vertex.h): position 3 x f32 at byte 0, morph start height f32
 * at 12, morph key f32 at 16. The normals, while the stream keeps them, are an array of their
 * own: 4 x snorm16 (x, y, z, 0) a vertex slot.
 */
export const STREAM_VERTEX_BYTES = 20;
export const STREAM_VERTEX_WORDS = 5;
export const STREAM_NORMAL_BYTES = 8;
export const RESTART_INDEX = 0xffffffff;

/** Steps of hexlod_terrain_frame (HEXLOD_FRAME_*): 0 runs the camera, one LOD update and the stream. */
export const FRAME = { all: 0, camera: 1, lod: 2, stream: 4, query: 8, hash: 16, census: 32 };

/** A failure reported by the core through hexlod_last_error(). */
export class CoreError extends Error {}

/**
 * Instantiates the core.
 * @param {{ wasmBinary?: Uint8Array, wasmUrl?: string, factory?: Function }} [options]
 *   wasmBinary in Node; in the browser the .wasm is fetched from wasmUrl (default: the product
 *   build next to this module). factory: another build's module factory (the diagnostics build,
 *   whose .wasm must then be the wasmBinary).
 * @returns {Promise<HexlodCore>}
 */
export async function createCore(options = {}) {
  const settings = {};
  if (options.wasmBinary) {
    settings.wasmBinary = options.wasmBinary;
  } else {
    const url = options.wasmUrl ?? new URL('../../build/wasm/hexlod_core.wasm', import.meta.url).href;
    settings.locateFile = () => url;
  }
  const module = await (options.factory ?? createHexlodCore)(settings);
  return new HexlodCore(module);
}

export class HexlodCore {
  constructor(module) {
    this.module = module;
    this.abiVersion = module._hexlod_abi_version();
  }

  /** The current WASM memory buffer (a new object after every growth). */
  get buffer() {
    return this.module.HEAPU8.buffer;
  }

  /** Whether this build exports the diagnostics ABI (src/api/hexlod_diagnostics.h). */
  get hasDiagnostics() {
    return typeof this.module._hexlod_diag_check_mesh === 'function';
  }

  /**
   * A typed-array view on WASM memory. Pointers from Emscripten 3.1.6 are signed 32-bit
   * numbers, so `>>> 0` recovers addresses above 2 GB.
   */
  view(ArrayType, pointer, length) {
    return new ArrayType(this.buffer, pointer >>> 0, length);
  }

  /** The last error message of the core. */
  lastError() {
    return this.module.UTF8ToString(this.module._hexlod_last_error());
  }

  /** Throws a CoreError with the core's message when `failed` is true. */
  check(failed, what) {
    if (failed) throw new CoreError(`${what}: ${this.lastError()}`);
  }

  /**
   * Creates a terrain whose samples JS writes in place (see Terrain.samples()).
   * @param {number} width samples per row
   * @param {number} height rows
   * @param {'u8'|'u16'|'i16'|'f32'} sampleType native depth of the heights
   */
  createTerrain(width, height, sampleType) {
    const type = SAMPLE_TYPES[sampleType];
    if (!type) throw new CoreError(`unknown sample type '${sampleType}'`);
    const handle = this.module._hexlod_terrain_create(width, height, type.code);
    this.check(handle === 0, `cannot create a ${width}x${height} ${sampleType} terrain`);
    const scratch = this.module._malloc(SCRATCH.bytes);
    if (scratch === 0) {
      this.module._hexlod_terrain_destroy(handle);
      throw new CoreError(`cannot create a ${width}x${height} ${sampleType} terrain: out of memory`);
    }
    return new Terrain(this, handle, width, height, sampleType, scratch);
  }
}

// The structs of src/api/hexlod.h in one block per terrain, allocated once: byte offsets
// (wasm32 layouts, asserted in src/api/hexlod_api.cpp).
const SCRATCH = {
  frame: 0, // hexlod_frame, 192 bytes
  camera: 192, // hexlod_camera, 112
  settings: 304, // hexlod_settings, 64
  scale: 368, // hexlod_scale, 48
  info: 416, // hexlod_field_info, 32
  levelView: 448, // hexlod_level_view, 24
  height: 472, // one double
  diagnostics: 480, // up to 8 doubles of a diagnostics call
  bytes: 544,
};

// hexlod_frame: doubles by Float64Array index, int32 by Int32Array index (from the struct's start).
const F64 = { updateMs: 0, tau: 1, frame: 2, memoryBytes: 3, triangles: 4, achievedErrorPx: 5 };
const I32 = {
  version: 12, converged: 13, operations: 14, splits: 15, merges: 16, cellsTested: 17, pendingMerges: 18,
  cells: 19, vertices: 20, maxLevel: 21, fullHexagons: 22, semiHexagons: 23, boundarySemiHexagons: 24,
  hashLow: 25, hashHigh: 26, vertexCount: 27, indexCount: 28, dirtyVertexPairs: 29, dirtyIndexPairs: 30,
  vertexPointer: 43, indexPointer: 44, dirtyVerticesPointer: 45, dirtyIndicesPointer: 46, normalsPointer: 47,
};

/**
 * The figures of the last hexlod_terrain_frame call, read through views on WASM memory: the
 * same object every frame, so a frame loop makes no garbage. Read a figure before the next
 * core call on the same terrain. Pointers are byte offsets (already `>>> 0`).
 */
export class FrameStats {
  constructor(terrain) {
    this.terrain = terrain;
  }

  f64(index) {
    return this.terrain.scratchF64()[this.terrain.frameF64 + index];
  }

  i32(index) {
    return this.terrain.scratchI32()[this.terrain.frameI32 + index];
  }

  /** Milliseconds of the last LOD update. */
  get updateMs() { return this.f64(F64.updateMs); }
  /** The tau in use in pixels (auto tau may have raised it). */
  get tau() { return this.f64(F64.tau); }
  /** The blends' frame counter: the shader's u_frame. */
  get frame() { return this.f64(F64.frame); }
  /** Bytes of the mesh structures, the refiner's caches and the stream. */
  get memoryBytes() { return this.f64(F64.memoryBytes); }
  get triangles() { return this.f64(F64.triangles); }
  /** With FRAME.census: the achieved screen error in pixels (-1 in max-error mode). */
  get achievedErrorPx() { return this.f64(F64.achievedErrorPx); }
  /** The stream's version: it moves whenever anything was written. */
  get version() { return this.i32(I32.version); }
  get converged() { return this.i32(I32.converged) === 1; }
  get operations() { return this.i32(I32.operations); }
  get splits() { return this.i32(I32.splits); }
  get merges() { return this.i32(I32.merges); }
  get cellsTested() { return this.i32(I32.cellsTested); }
  get pendingMerges() { return this.i32(I32.pendingMerges); }
  get cells() { return this.i32(I32.cells); }
  get vertices() { return this.i32(I32.vertices); }
  get maxLevel() { return this.i32(I32.maxLevel); }
  /** With FRAME.census: live cells by kind (paper §4.2). */
  get fullHexagons() { return this.i32(I32.fullHexagons); }
  get semiHexagons() { return this.i32(I32.semiHexagons); }
  get boundarySemiHexagons() { return this.i32(I32.boundarySemiHexagons); }
  /** With FRAME.hash: the mesh hash's halves as unsigned numbers. */
  get hashLow() { return this.i32(I32.hashLow) >>> 0; }
  get hashHigh() { return this.i32(I32.hashHigh) >>> 0; }
  /** Vertex slots of the pool and indices of the index array. */
  get vertexCount() { return this.i32(I32.vertexCount); }
  get indexCount() { return this.i32(I32.indexCount); }
  /** (first, count) pairs written since the last acknowledgeStream(). */
  get dirtyVertexPairs() { return this.i32(I32.dirtyVertexPairs); }
  get dirtyIndexPairs() { return this.i32(I32.dirtyIndexPairs); }
  get vertexPointer() { return this.i32(I32.vertexPointer) >>> 0; }
  get indexPointer() { return this.i32(I32.indexPointer) >>> 0; }
  get dirtyVerticesPointer() { return this.i32(I32.dirtyVerticesPointer) >>> 0; }
  get dirtyIndicesPointer() { return this.i32(I32.dirtyIndicesPointer) >>> 0; }
  /** The vertex normals (STREAM_NORMAL_BYTES a slot), or 0 while the stream keeps none. */
  get normalsPointer() { return this.i32(I32.normalsPointer) >>> 0; }

  /** The mesh hash as 16 hexadecimal digits (high half first; a string, so not per frame). */
  hash() {
    const hex = (half) => half.toString(16).padStart(8, '0');
    return hex(this.hashHigh) + hex(this.hashLow);
  }
}

/** What the setters keep, mirrored from hexlod_settings (the core's defaults). */
function defaultSettings() {
  return {
    tau: 1, maxError: 0, verticalScale: 1, budgetMs: 0, maxOperations: 0, maxTriangles: 0, autoTau: false,
    culling: true, backfaceCulling: true, morphFrames: 0, layout: 'fans', normals: true,
  };
}

const positive = (value) => Number.isFinite(value) && value > 0;

/** One height field in the core, and the mesh built from it. */
export class Terrain {
  constructor(core, handle, width, height, sampleType, scratch) {
    this.core = core;
    this.handle = handle;
    this.width = width;
    this.height = height;
    this.sampleType = sampleType;
    this.scratch = scratch >>> 0;
    this.frameF64 = this.scratch / 8; // the frame struct's first double and int32 in the views
    this.frameI32 = this.scratch / 4;
    this.f64View = null;
    this.i32View = null;
    this.hasMesh = false;
    this.settings = defaultSettings();
    this.stats = new FrameStats(this);
  }

  get m() {
    if (this.handle === 0) throw new CoreError('the terrain was destroyed');
    return this.core.module;
  }

  /** A Float64Array over all WASM memory, made again only after the memory grew. */
  scratchF64() {
    if (this.f64View === null || this.f64View.buffer !== this.core.buffer) this.f64View = new Float64Array(this.core.buffer);
    return this.f64View;
  }

  /** An Int32Array over all WASM memory, made again only after the memory grew. */
  scratchI32() {
    if (this.i32View === null || this.i32View.buffer !== this.core.buffer) this.i32View = new Int32Array(this.core.buffer);
    return this.i32View;
  }

  /** Frees the terrain in the core; further calls throw. */
  destroy() {
    if (this.handle !== 0) {
      this.core.module._hexlod_terrain_destroy(this.handle);
      this.core.module._free(this.scratch);
    }
    this.handle = 0;
  }

  // --- The height field ------------------------------------------------------------------------

  /** A fresh view on the samples, to decode a file straight into WASM memory. */
  samples() {
    const pointer = this.m._hexlod_terrain_samples(this.handle);
    this.core.check(pointer === 0, 'no samples');
    return this.core.view(SAMPLE_TYPES[this.sampleType].Array, pointer, this.width * this.height);
  }

  /** Size of the samples in bytes. */
  get sampleBytes() {
    return this.width * this.height * SAMPLE_TYPES[this.sampleType].Array.BYTES_PER_ELEMENT;
  }

  /**
   * How samples become metres (hexlod_terrain_set_scale). With a mesh, the mesh is rebuilt.
   * @param {{spacingX: number, spacingY: number, heightScale: number, heightOffset: number, nodata: number|null}} s
   *   spacings in metres per sample, metres = raw * heightScale + heightOffset, nodata a raw value or null.
   */
  setScale({ spacingX, spacingY, heightScale, heightOffset, nodata }) {
    // The struct takes 0 as "default"; this method's callers mean a real 0, which is invalid.
    if (spacingX === 0 || spacingY === 0) throw new CoreError('invalid height scale: sample spacing must be positive');
    if (heightScale === 0) throw new CoreError('invalid height scale: height scale must not be zero');
    const hasNodata = nodata !== null && nodata !== undefined && !Number.isNaN(nodata);
    const base = (this.scratch + SCRATCH.scale) / 8, f64 = this.scratchF64();
    f64[base] = spacingX;
    f64[base + 1] = spacingY;
    f64[base + 2] = heightScale;
    f64[base + 3] = heightOffset;
    f64[base + 4] = hasNodata ? nodata : 0;
    const i32 = this.scratchI32(), ibase = (this.scratch + SCRATCH.scale) / 4;
    i32[ibase + 10] = hasNodata ? 1 : 0;
    i32[ibase + 11] = 0;
    this.core.check(this.m._hexlod_terrain_set_scale(this.handle, this.scratch + SCRATCH.scale) < 0, 'invalid height scale');
    this.spacingX = spacingX;
    this.spacingY = spacingY;
  }

  /** Fills missing samples and computes the height range; returns how many were missing. */
  prepare() {
    const info = this.scratch + SCRATCH.info;
    this.core.check(this.m._hexlod_terrain_prepare(this.handle, info) < 0, 'cannot use this height field');
    const f64 = this.scratchF64(), base = info / 8;
    this.minHeight = f64[base];
    this.maxHeight = f64[base + 1];
    return f64[base + 2];
  }

  /** Bilinear height in metres at (x, z) metres, clamped to the field. */
  heightAt(x, z) {
    return this.readHeight(x, z, 0);
  }

  /**
   * Height in metres (unscaled) of the surface as drawn now, geomorph blends included, at
   * (x, z) metres; NaN where nothing is drawn (outside the domain, or no mesh). After updateStream.
   */
  drawnHeightAt(x, z) {
    if (!this.hasMesh) return NaN;
    return this.readHeight(x, z, 1);
  }

  readHeight(x, z, surface) {
    const pointer = this.scratch + SCRATCH.height;
    const covered = this.m._hexlod_terrain_height_at(this.handle, x, z, surface, pointer);
    this.core.check(covered < 0, 'cannot read a height');
    return covered === 1 ? this.scratchF64()[pointer / 8] : NaN;
  }

  // --- The hexagon mesh (paper §4) ---------------------------------------------------------------

  /**
   * (Re)creates the hexagon mesh over the whole field (paper §4.7).
   * @param {'shifted'|'exact'} embedding the paper's shifted rows, or vertices on their samples
   */
  resetMesh(embedding = 'exact') {
    const code = EMBEDDINGS[embedding];
    if (code === undefined) throw new CoreError(`unknown embedding '${embedding}'`);
    const pointer = this.scratch + SCRATCH.settings; // hexlod_mesh_settings, borrowed
    this.scratchI32()[pointer / 4] = code;
    this.core.check(this.m._hexlod_terrain_reset_mesh(this.handle, pointer) < 0, 'cannot create the hexagon mesh');
    this.hasMesh = true;
  }

  /** Figures of the hexagon mesh: triangles, cells, vertices, max level, bytes. */
  meshStats() {
    const s = this.query();
    return { triangles: s.triangles, cells: s.cells, vertices: s.vertices, maxLevel: s.maxLevel, bytes: s.memoryBytes };
  }

  /** Live cells by kind (paper §4.2): {full, semi, boundarySemi}. A pass over the cells. */
  cellKinds() {
    const s = this.query(FRAME.census);
    return { full: s.fullHexagons, semi: s.semiHexagons, boundarySemi: s.boundarySemiHexagons };
  }

  /** The mesh hash as 16 hexadecimal digits (high half first). */
  meshHash() {
    return this.query(FRAME.hash).hash();
  }

  /**
   * The level-ordered view for diagnostics, written anew: every cell's fan grouped by level,
   * levelOffsets (max level + 2 entries), and with outline every cell edge once as a line pair.
   * Views valid until the next core call.
   */
  levelView(outline = false) {
    const pointer = this.scratch + SCRATCH.levelView;
    const count = this.m._hexlod_terrain_level_view(this.handle, outline ? 1 : 0, pointer);
    this.core.check(count < 0, 'cannot build the level view');
    const i32 = this.scratchI32(), base = pointer / 4, core = this.core;
    return {
      indices: core.view(Uint32Array, i32[base], i32[base + 3]),
      levelOffsets: core.view(Int32Array, i32[base + 1], i32[base + 4]),
      outline: core.view(Uint32Array, i32[base + 2], i32[base + 5]),
    };
  }

  // --- One frame (paper §5-§7) -------------------------------------------------------------------

  /**
   * One frame in one core call (hexlod_terrain_frame): the camera (null keeps the last one),
   * one LOD update within the budget, the stream. Returns this.stats, the same FrameStats
   * object every time.
   * @param {object|null} camera as setLodCamera takes it
   * @param {number} [steps] FRAME bits: 0 all steps; FRAME.hash / FRAME.census add figures
   */
  frame(camera, steps = FRAME.all) {
    if (camera) this.writeCamera(camera);
    const result = this.m._hexlod_terrain_frame(this.handle, camera ? this.scratch + SCRATCH.camera : 0, steps,
      this.scratch + SCRATCH.frame);
    if (result < 0) {
      const message = this.core.lastError();
      throw new CoreError(`${message.startsWith('degenerate camera') ? 'invalid camera' : 'cannot run the frame'}: ${message}`);
    }
    return this.stats;
  }

  /** Fills this.stats without changing anything (extra: FRAME.hash, FRAME.census). */
  query(extra = 0) {
    return this.frame(null, FRAME.query | extra);
  }

  writeCamera({ eye, target, up = [0, 1, 0], fovY, tanHalfFovY, aspect, viewportHeight, near, far }) {
    const f64 = this.scratchF64(), base = (this.scratch + SCRATCH.camera) / 8;
    for (let c = 0; c < 3; c++) {
      f64[base + c] = eye[c];
      f64[base + 3 + c] = target[c];
      f64[base + 6 + c] = up[c];
    }
    f64[base + 9] = tanHalfFovY ?? Math.tan(fovY / 2);
    f64[base + 10] = aspect;
    f64[base + 11] = viewportHeight;
    f64[base + 12] = near;
    f64[base + 13] = far;
  }

  /**
   * Sets the camera of view-dependent refinement.
   * @param {{eye: number[], target: number[], up?: number[], fovY?: number, tanHalfFovY?: number,
   *   aspect: number, viewportHeight: number, near: number, far: number}} camera
   *   eye and target in metres (x east, y up times the vertical scale, z south); up defaults
   *   to +y; fovY is the vertical field of view in radians, or give tanHalfFovY directly;
   *   aspect = viewport width / height; viewportHeight in device pixels; near, far in metres.
   */
  setLodCamera(camera) {
    this.frame(camera, FRAME.camera);
  }

  /** One refinement step within the budget; returns the number of operations it made. */
  updateLod() {
    return this.frame(null, FRAME.lod).operations;
  }

  /** True when the last update converged and no merge waits for a fade-out. */
  lodConverged() {
    return this.query().converged;
  }

  /** Figures of the last update: {frame, pendingMerges, converged, splits, merges, updateMs, tau}. */
  lodStats() {
    const s = this.query();
    return {
      frame: s.frame, pendingMerges: s.pendingMerges, converged: s.converged, splits: s.splits, merges: s.merges,
      updateMs: s.updateMs, tau: s.tau,
    };
  }

  /** The blends' frame counter: the shader's u_frame. */
  lodFrame() {
    return this.query().frame;
  }

  /**
   * The achieved screen error in pixels of the current mesh for the current camera; -1 in
   * max-error mode. A pass over the cells.
   */
  achievedErrorPx() {
    return this.query(FRAME.census).achievedErrorPx;
  }

  /**
   * Applies the mesh's changes to the fan stream; call after updateLod.
   * @returns {number} the stream version: it moves whenever anything was written
   */
  updateStream() {
    return this.frame(null, FRAME.stream).version;
  }

  /** The stream's version: it moves whenever anything was written. */
  streamVersion() {
    return this.query().version;
  }

  /**
   * Views on the fan stream, valid until the next core call (src/api/hexlod.h, hexlod_frame):
   * the vertex pool as bytes (STREAM_VERTEX_BYTES a slot) and as floats (STREAM_VERTEX_WORDS a
   * slot; the position comes first), the index array, and the ranges written since the last
   * acknowledgeStream() as [first, count] pairs of vertex slots and of indices.
   */
  stream() {
    const s = this.query(), core = this.core;
    const vertexCount = s.vertexCount, vertexPointer = s.vertexPointer;
    const ranges = (pointer, pairs) => (pairs > 0 ? core.view(Int32Array, pointer, 2 * pairs) : new Int32Array(0));
    return {
      version: s.version,
      vertexCount,
      vertexBytes: core.view(Uint8Array, vertexPointer, vertexCount * STREAM_VERTEX_BYTES),
      vertices: core.view(Float32Array, vertexPointer, vertexCount * STREAM_VERTEX_WORDS),
      indices: core.view(Uint32Array, s.indexPointer, s.indexCount),
      dirtyVertices: ranges(s.dirtyVerticesPointer, s.dirtyVertexPairs),
      dirtyIndices: ranges(s.dirtyIndicesPointer, s.dirtyIndexPairs),
    };
  }

  /** The renderer has uploaded every dirty range. */
  acknowledgeStream() {
    this.core.check(this.m._hexlod_terrain_acknowledge(this.handle) < 0, 'cannot acknowledge the stream');
  }

  // --- Settings (hexlod_settings: everything but the camera) -------------------------------------

  /** Writes this.settings to the core; on failure the previous settings stay, here and there. */
  applySettings(change, what) {
    const previous = this.settings;
    this.settings = { ...previous, ...change };
    const s = this.settings, base = this.scratch + SCRATCH.settings;
    const f64 = this.scratchF64(), i32 = this.scratchI32(), d = base / 8, i = base / 4;
    f64[d] = s.tau;
    f64[d + 1] = s.maxError;
    f64[d + 2] = s.verticalScale;
    f64[d + 3] = Number.isFinite(s.budgetMs) && s.budgetMs > 0 ? s.budgetMs : 0;
    i32[i + 8] = s.maxOperations > 0 ? s.maxOperations : 0;
    i32[i + 9] = s.maxTriangles > 0 ? s.maxTriangles : 0;
    i32[i + 10] = s.autoTau ? 1 : 0;
    i32[i + 11] = s.culling ? 0 : 1;
    i32[i + 12] = s.backfaceCulling ? 0 : 1;
    i32[i + 13] = s.morphFrames;
    i32[i + 14] = STREAM_LAYOUTS[s.layout];
    i32[i + 15] = s.normals ? 0 : 1;
    if (this.m._hexlod_terrain_set_settings(this.handle, base) < 0) {
      this.settings = previous;
      throw new CoreError(`${what}: ${this.core.lastError()}`);
    }
  }

  /** Screen-space tolerance tau in device pixels (> 0); switches to view-dependent mode. */
  setLodTolerance(tauPx) {
    if (!positive(tauPx)) throw new CoreError('invalid tolerance: tau must be a positive number of pixels');
    this.applySettings({ tau: tauPx, maxError: 0 }, 'invalid tolerance');
  }

  /** Maximum vertical error in metres (> 0); switches to view-independent mode. */
  setLodMaxError(maxErrorM) {
    if (!positive(maxErrorM)) throw new CoreError('invalid maximum error: the maximum error must be a positive number of metres');
    this.applySettings({ maxError: maxErrorM }, 'invalid maximum error');
  }

  /** Heights are drawn times verticalScale (> 0); every cell is re-evaluated. */
  setLodVerticalScale(verticalScale) {
    if (!positive(verticalScale)) throw new CoreError('invalid vertical scale: the vertical scale must be a positive number');
    this.applySettings({ verticalScale }, 'invalid vertical scale');
  }

  /**
   * Per-update budget: at most budgetMs milliseconds (<= 0: no limit) and at most maxOperations
   * splits and merges (<= 0: no limit).
   */
  setLodBudget(budgetMs = 0, maxOperations = 0) {
    this.applySettings({ budgetMs, maxOperations }, 'invalid budget');
  }

  /** Cap on drawn triangles (<= 0: none), and whether tau may rise and fall to respect it. */
  setLodLimits(maxTriangles = 0, autoTau = false) {
    this.applySettings({ maxTriangles, autoTau }, 'invalid limits');
  }

  /** Frustum culling of cells (on by default). */
  setLodCulling(enabled) {
    this.applySettings({ culling: Boolean(enabled) }, 'cannot set culling');
  }

  /** Back-face culling by the cone of normals on (default) or off. */
  setLodBackfaceCulling(enabled) {
    this.applySettings({ backfaceCulling: Boolean(enabled) }, 'cannot set back-face culling');
  }

  /** Geomorphing over `frames` frames (0 = off, at most 1000; paper §7). */
  setMorphFrames(frames) {
    this.applySettings({ morphFrames: frames }, 'invalid morph frames');
  }

  /** 'fans' (TRIANGLE_FAN with primitive restart, 9 indices a cell) or 'triangles' (18). */
  setStreamLayout(layout) {
    if (STREAM_LAYOUTS[layout] === undefined) throw new TypeError(`unknown stream layout ${layout} (expected fans or triangles)`);
    this.applySettings({ layout }, 'cannot set the stream layout');
  }

  /**
   * Whether the stream keeps the mesh's vertex normals (paper §7): the viewer needs them only
   * for mesh normals, the plain mode, and until the field's own normals are ready. Off saves
   * 32 bytes a vertex (the normal and its exact sum) and the normal arithmetic; turning them on
   * rebuilds them all.
   */
  setStreamNormals(on) {
    if (on === this.streamNormals) return;
    this.applySettings({ normals: Boolean(on) }, 'cannot switch the stream normals');
    this.streamNormals = on;
  }

  // --- Diagnostics (src/api/hexlod_diagnostics.h: the diagnostics build only, e.g. in Node) -------

  /** The diagnostics function `name`, or a CoreError saying which build has it. */
  diagnostic(name) {
    const fn = this.m[`_hexlod_diag_${name}`];
    if (typeof fn !== 'function') {
      throw new CoreError(`${name} is a diagnostic: load the diagnostics build (build/wasm-diag, bin/node_core.js)`);
    }
    return fn;
  }

  /** Calls a diagnostics function that writes `length` doubles; returns them as an array. */
  readDiagnostic(name, length, what, ...args) {
    const pointer = this.scratch + SCRATCH.diagnostics;
    this.core.check(this.diagnostic(name)(this.handle, ...args, pointer) < 0, what);
    return Array.from(this.scratchF64().subarray(pointer / 8, pointer / 8 + length));
  }

  /** Uniform split, `rounds` times (each quadruples the triangles); returns the splits made. */
  refineUniform(rounds) {
    const splits = this.diagnostic('refine_uniform')(this.handle, rounds);
    this.core.check(splits < 0, 'cannot refine');
    return splits;
  }

  /** Runs the core's invariant check; throws a CoreError naming the first violation. */
  checkMesh() {
    this.core.check(this.diagnostic('check_mesh')(this.handle) < 0, 'mesh invariant violated');
  }

  /**
   * Measures the mesh against the samples (a pass over every sample).
   * @param {boolean} againstStored true: the field the core stores (shifted rows interpolated
   *   for the shifted embedding); false: the original samples at their true positions
   * @returns {{max: number, p99: number, mean: number, uncovered: number}} metres, and samples
   */
  measureError(againstStored = false) {
    const [max, p99, mean, uncovered] = this.readDiagnostic('measure_error', 4, 'cannot measure the error',
      againstStored ? 1 : 0);
    return { max, p99, mean, uncovered };
  }

  /**
   * The largest screen-space jump of any vertex since the last call, for benchmarks:
   * {maxJumpPx, jumpsOverHalfPx, measured, at: {x, y, depth, kind}}, where at is the largest
   * jump's screen position (pixels from the centre), depth (metres) and whether its vertex was
   * kept, new or freed.
   */
  measurePopping() {
    const [maxJumpPx, jumpsOverHalfPx, measured, x, y, depth, kind] = this.readDiagnostic('measure_popping', 7,
      'cannot measure popping');
    return { maxJumpPx, jumpsOverHalfPx, measured, at: { x, y, depth, kind: ['kept', 'new', 'freed'][kind] } };
  }
}
