// The one JS module that owns the WebAssembly core (src/hexlod.h is the ABI it wraps).
// It runs unchanged in the browser, in workers and in Node; only how the .wasm bytes are found
// differs (the browser fetches them next to this module, Node passes `wasmBinary`).
//
// WASM memory may grow during any core call, which detaches every typed-array view on the old
// buffer: views are therefore made on demand through `HexlodCore.view`, never cached by callers.
import createHexlodCore from '../build/wasm/hexlod_core.mjs';

/** Sample type names of the loaders mapped to HEXLOD_SAMPLE_* and typed-array constructors. */
export const SAMPLE_TYPES = {
  u8: { code: 1, Array: Uint8Array },
  u16: { code: 2, Array: Uint16Array },
  i16: { code: 3, Array: Int16Array },
  f32: { code: 4, Array: Float32Array },
};

/** Index layouts of the fan stream (HEXLOD_LAYOUT_*). */
export const STREAM_LAYOUTS = { fans: 0, triangles: 1 };
/**
 * A stream vertex (src/stream_vertex.h): position 3 x f32 at byte 0, normal 4 x snorm16 at 12,
 * morph start 3 x f32 at 20, morph key f32 at 32.
 */
export const STREAM_VERTEX_BYTES = 36;
export const STREAM_VERTEX_WORDS = 9;
export const RESTART_INDEX = 0xffffffff;

/** A failure reported by the core through hexlod_last_error(). */
export class CoreError extends Error {}

/**
 * Instantiates the core.
 * @param {{ wasmBinary?: Uint8Array, wasmUrl?: string }} [options] wasmBinary in Node; in the
 *   browser the .wasm is fetched from wasmUrl (default: the build next to this module).
 * @returns {Promise<HexlodCore>}
 */
export async function createCore(options = {}) {
  const settings = {};
  if (options.wasmBinary) {
    settings.wasmBinary = options.wasmBinary;
  } else {
    const url = options.wasmUrl ?? new URL('../build/wasm/hexlod_core.wasm', import.meta.url).href;
    settings.locateFile = () => url;
  }
  const module = await createHexlodCore(settings);
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

  /**
   * A typed-array view on WASM memory. Pointers from Emscripten 3.1.6 are signed 32-bit
   * numbers, so `>>> 0` recovers addresses above 2 GB.
   */
  view(ArrayType, pointer, length) {
    return new ArrayType(this.buffer, pointer >>> 0, length);
  }

  /**
   * Calls a core function that writes `length` values of ArrayType to an out-pointer:
   * `call(pointer)` returns its result code (< 0: a CoreError "what: <core message>").
   * Returns a copy of the values; the scratch memory is freed either way.
   */
  readOutput(ArrayType, length, what, call) {
    const pointer = this.module._malloc(length * ArrayType.BYTES_PER_ELEMENT);
    this.check(pointer === 0, `${what}: out of memory`);
    try {
      this.check(call(pointer) < 0, what);
      return Array.from(this.view(ArrayType, pointer, length));
    } finally {
      this.module._free(pointer);
    }
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
    return new Terrain(this, handle, width, height, sampleType);
  }
}

/** One height field in the core, and the meshes built from it. */
export class Terrain {
  constructor(core, handle, width, height, sampleType) {
    this.core = core;
    this.handle = handle;
    this.width = width;
    this.height = height;
    this.sampleType = sampleType;
  }

  get m() {
    if (this.handle === 0) throw new CoreError('the terrain was destroyed');
    return this.core.module;
  }

  /** A fresh view on the samples, to decode a file straight into WASM memory. */
  samples() {
    const pointer = this.m._hexlod_terrain_samples(this.handle);
    return this.core.view(SAMPLE_TYPES[this.sampleType].Array, pointer, this.width * this.height);
  }

  /**
   * How samples become metres.
   * @param {{spacingX: number, spacingY: number, heightScale: number, heightOffset: number, nodata: number|null}} s
   *   spacings in metres per sample, metres = raw * heightScale + heightOffset, nodata a raw value or null.
   */
  setScale({ spacingX, spacingY, heightScale, heightOffset, nodata }) {
    const hasNodata = nodata !== null && nodata !== undefined && !Number.isNaN(nodata);
    const result = this.m._hexlod_terrain_set_scale(this.handle, spacingX, spacingY, heightScale,
      heightOffset, hasNodata ? 1 : 0, hasNodata ? nodata : 0);
    this.core.check(result < 0, 'invalid height scale');
    this.spacingX = spacingX;
    this.spacingY = spacingY;
  }

  /** Fills missing samples and computes the height range; returns how many were missing. */
  prepare() {
    const missing = this.m._hexlod_terrain_prepare(this.handle);
    this.core.check(missing < 0, 'cannot use this height field');
    this.minHeight = this.m._hexlod_terrain_min_height(this.handle);
    this.maxHeight = this.m._hexlod_terrain_max_height(this.handle);
    return missing;
  }

  /** Bilinear height in metres at (x, z) metres, clamped to the field. */
  heightAt(x, z) {
    return this.m._hexlod_terrain_height_at(this.handle, x, z);
  }

  /** Size of the samples in bytes. */
  get sampleBytes() {
    return this.m._hexlod_terrain_sample_bytes(this.handle);
  }

  /**
   * (Re)creates the hexagon mesh over the whole field (paper §4.7).
   * @param {'shifted'|'exact'} embedding the paper's shifted rows, or vertices on their samples
   */
  resetMesh(embedding = 'exact') {
    const code = { shifted: 0, exact: 1 }[embedding];
    if (code === undefined) throw new CoreError(`unknown embedding '${embedding}'`);
    this.core.check(this.m._hexlod_mesh_reset(this.handle, code) < 0, 'cannot create the hexagon mesh');
  }

  /** Uniform split, `rounds` times (each quadruples the triangles); returns the splits made. */
  refineUniform(rounds) {
    const splits = this.m._hexlod_mesh_refine_uniform(this.handle, rounds);
    this.core.check(splits < 0, 'cannot refine');
    return splits;
  }

  /** Figures of the hexagon mesh: triangles, cells, vertices, max level, bytes. */
  meshStats() {
    const m = this.m, h = this.handle;
    return {
      triangles: m._hexlod_mesh_triangle_count(h),
      cells: m._hexlod_mesh_cell_count(h),
      vertices: m._hexlod_mesh_vertex_count(h),
      maxLevel: m._hexlod_mesh_max_level(h),
      bytes: m._hexlod_mesh_memory_bytes(h),
    };
  }

  /** Live cells by kind (hexlod_mesh_cell_kinds): {full, semi, boundarySemi}. */
  cellKinds() {
    const [full, semi, boundarySemi] = this.core.readOutput(Int32Array, 3, 'cannot count cells',
      (out) => this.m._hexlod_mesh_cell_kinds(this.handle, out));
    return { full, semi, boundarySemi };
  }

  /**
   * Height in metres (unscaled) of the surface as drawn now, geomorph blends included, at
   * (x, z) metres (hexlod_stream_drawn_height_at); NaN where nothing is drawn. After updateStream.
   */
  drawnHeightAt(x, z) {
    return this.m._hexlod_stream_drawn_height_at(this.handle, x, z);
  }

  /** Runs the core's invariant check; throws a CoreError naming the first violation. */
  checkMesh() {
    this.core.check(this.m._hexlod_mesh_check(this.handle) < 0, 'mesh invariant violated');
  }

  /**
   * Applies the mesh's changes to the fan stream (hexlod_stream_update); call after updateLod.
   * @returns {number} the stream version: it moves whenever anything was written
   */
  updateStream() {
    const version = this.m._hexlod_stream_update(this.handle);
    this.core.check(version < 0, 'cannot update the fan stream');
    return version;
  }

  /** The stream's version (hexlod_stream_version): it moves whenever anything was written. */
  streamVersion() {
    const version = this.m._hexlod_stream_version(this.handle);
    this.core.check(version < 0, 'no fan stream');
    return version;
  }

  /** 'fans' (TRIANGLE_FAN with primitive restart, 9 indices a cell) or 'triangles' (18). */
  setStreamLayout(layout) {
    const code = STREAM_LAYOUTS[layout];
    if (code === undefined) throw new TypeError(`unknown stream layout ${layout} (expected fans or triangles)`);
    this.core.check(this.m._hexlod_stream_set_layout(this.handle, code) < 0, 'cannot set the stream layout');
  }

  /**
   * Whether the stream keeps the mesh's vertex normals (paper §7): the viewer needs them only
   * for mesh normals, the plain mode, and until the field's own normals are ready. Off saves
   * 24 bytes a vertex and the normal arithmetic; turning them on rebuilds them all.
   */
  setStreamNormals(on) {
    if (on === this.streamNormals) return;
    this.core.check(this.m._hexlod_stream_set_normals(this.handle, on ? 1 : 0) < 0, 'cannot switch the stream normals');
    this.streamNormals = on;
  }

  /**
   * Views on the fan stream, valid until the next core call (src/hexlod.h, "The fan stream"):
   * the vertex pool as bytes (STREAM_VERTEX_BYTES a slot) and as floats (STREAM_VERTEX_WORDS a
   * slot; the position comes first), the index array, and the ranges written since the last
   * acknowledgeStream() as [first, count] pairs of vertex slots and of indices.
   */
  stream() {
    const m = this.m, h = this.handle, core = this.core;
    const vertexCount = m._hexlod_stream_vertex_count(h);
    const indexCount = m._hexlod_stream_index_count(h);
    core.check(vertexCount < 0 || indexCount < 0, 'no fan stream');
    const pairs = m._malloc(4);
    try {
      const ranges = (fn) => {
        const pointer = fn(h, pairs);
        const count = core.view(Int32Array, pairs, 1)[0];
        return count > 0 ? core.view(Int32Array, pointer, 2 * count) : new Int32Array(0);
      };
      const vertexPointer = m._hexlod_stream_vertices(h);
      return {
        version: m._hexlod_stream_version(h),
        vertexCount,
        vertexBytes: core.view(Uint8Array, vertexPointer, vertexCount * STREAM_VERTEX_BYTES),
        vertices: core.view(Float32Array, vertexPointer, vertexCount * STREAM_VERTEX_WORDS),
        indices: core.view(Uint32Array, m._hexlod_stream_indices(h), indexCount),
        dirtyVertices: ranges(m._hexlod_stream_dirty_vertices),
        dirtyIndices: ranges(m._hexlod_stream_dirty_indices),
      };
    } finally {
      m._free(pairs);
    }
  }

  /** The renderer has uploaded every dirty range (hexlod_stream_acknowledge). */
  acknowledgeStream() {
    this.core.check(this.m._hexlod_stream_acknowledge(this.handle) < 0, 'cannot acknowledge the stream');
  }

  /**
   * The level-ordered view for diagnostics, written anew: every cell's fan grouped by level,
   * levelOffsets (max level + 2 entries), and with outline every cell edge once as a line pair.
   * Views valid until the next core call.
   */
  levelView(outline = false) {
    const m = this.m, h = this.handle, core = this.core;
    const count = m._hexlod_stream_build_level_view(h, outline ? 1 : 0);
    core.check(count < 0, 'cannot build the level view');
    return {
      indices: core.view(Uint32Array, m._hexlod_stream_level_indices(h), count),
      levelOffsets: core.view(Int32Array, m._hexlod_stream_level_offsets(h), m._hexlod_mesh_max_level(h) + 2),
      outline: core.view(Uint32Array, m._hexlod_stream_outline(h), m._hexlod_stream_outline_count(h)),
    };
  }

  /** Frees the terrain in the core; further calls throw. */
  destroy() {
    if (this.handle !== 0) this.core.module._hexlod_terrain_destroy(this.handle);
    this.handle = 0;
  }
}

// --- View-dependent refinement (src/hexlod.h, "View-dependent refinement", paper §5, §6) -------
// Methods added to Terrain: each wraps one hexlod_lod_* function (or the mesh hash and error
// measure) and throws a CoreError with the core's message when it fails.

/** The per-update figures of the refiner (hexlod_lod_last_* and hexlod_lod_converged). */
function lodFigures(m, h) {
  return {
    frame: m._hexlod_lod_frame(h),
    pendingMerges: m._hexlod_lod_pending_merges(h),
    converged: m._hexlod_lod_converged(h) === 1,
    splits: m._hexlod_lod_last_splits(h),
    merges: m._hexlod_lod_last_merges(h),
    updateMs: m._hexlod_lod_last_update_ms(h),
    tau: m._hexlod_lod_current_tau(h),
  };
}

Object.assign(Terrain.prototype, {
  /**
   * Sets the camera of view-dependent refinement (hexlod_lod_set_camera).
   * @param {{eye: number[], target: number[], up?: number[], fovY?: number, tanHalfFovY?: number,
   *   aspect: number, viewportHeight: number, near: number, far: number}} camera
   *   eye and target in metres (x east, y up times the vertical scale, z south); up defaults
   *   to +y; fovY is the vertical field of view in radians, or give tanHalfFovY directly;
   *   aspect = viewport width / height; viewportHeight in device pixels; near, far in metres.
   */
  setLodCamera({ eye, target, up = [0, 1, 0], fovY, tanHalfFovY, aspect, viewportHeight, near, far }) {
    const tangent = tanHalfFovY ?? Math.tan(fovY / 2);
    const result = this.m._hexlod_lod_set_camera(this.handle, eye[0], eye[1], eye[2], target[0], target[1],
      target[2], up[0], up[1], up[2], tangent, aspect, viewportHeight, near, far);
    this.core.check(result < 0, 'invalid camera');
  },

  /** Screen-space tolerance tau in device pixels (> 0); switches to view-dependent mode. */
  setLodTolerance(tauPx) {
    this.core.check(this.m._hexlod_lod_set_tolerance(this.handle, tauPx) < 0, 'invalid tolerance');
  },

  /** Maximum vertical error in metres (> 0); switches to view-independent mode. */
  setLodMaxError(maxErrorM) {
    this.core.check(this.m._hexlod_lod_set_max_error(this.handle, maxErrorM) < 0, 'invalid maximum error');
  },

  /** Heights are drawn times verticalScale (> 0); every cell is re-evaluated. */
  setLodVerticalScale(verticalScale) {
    this.core.check(this.m._hexlod_lod_set_vertical_scale(this.handle, verticalScale) < 0,
      'invalid vertical scale');
  },

  /**
   * Per-update budget: at most budgetMs milliseconds (<= 0: no limit) and at most maxOperations
   * splits and merges (<= 0: no limit).
   */
  setLodBudget(budgetMs = 0, maxOperations = 0) {
    this.core.check(this.m._hexlod_lod_set_budget(this.handle, budgetMs, maxOperations) < 0, 'invalid budget');
  },

  /** Cap on drawn triangles (<= 0: none), and whether tau may rise and fall to respect it. */
  setLodLimits(maxTriangles = 0, autoTau = false) {
    this.core.check(this.m._hexlod_lod_set_limits(this.handle, maxTriangles, autoTau ? 1 : 0) < 0,
      'invalid limits');
  },

  /** Frustum culling of cells (on by default). */
  setLodCulling(enabled) {
    this.core.check(this.m._hexlod_lod_set_culling(this.handle, enabled ? 1 : 0) < 0, 'cannot set culling');
  },

  /** Back-face culling by the cone of normals on (default) or off (hexlod_lod_set_backface_culling). */
  setLodBackfaceCulling(enabled) {
    this.core.check(this.m._hexlod_lod_set_backface_culling(this.handle, enabled ? 1 : 0) < 0, 'cannot set back-face culling');
  },

  /** Geomorphing over `frames` frames (0 = off, at most 1000; paper §7). */
  setMorphFrames(frames) {
    this.core.check(this.m._hexlod_lod_set_morph_frames(this.handle, frames) < 0, 'invalid morph frames');
  },

  /** The blends' frame counter: the shader's u_frame. */
  lodFrame() {
    return this.m._hexlod_lod_frame(this.handle);
  },

  /**
   * The largest screen-space jump of any vertex since the last call, for benchmarks
   * (hexlod_measure_popping): {maxJumpPx, jumpsOverHalfPx, measured, at: {x, y, depth, kind}}, where
   * at is the largest jump's screen position (pixels from the centre), depth (metres) and
   * whether its vertex was kept, new or freed.
   */
  measurePopping() {
    const [maxJumpPx, jumpsOverHalfPx, measured, x, y, depth, kind] = this.core.readOutput(Float64Array, 7,
      'cannot measure popping', (out) => this.m._hexlod_measure_popping(this.handle, out));
    return { maxJumpPx, jumpsOverHalfPx, measured, at: { x, y, depth, kind: ['kept', 'new', 'freed'][kind] } };
  },

  /** One refinement step within the budget; returns the number of operations it made. */
  updateLod() {
    const operations = this.m._hexlod_lod_update(this.handle);
    this.core.check(operations < 0, 'cannot update the level of detail');
    return operations;
  },

  /** True when the last update changed nothing. */
  lodConverged() {
    return this.m._hexlod_lod_converged(this.handle) === 1;
  },

  /** Figures of the last update: {converged, splits, merges, updateMs, tau}. */
  lodStats() {
    return lodFigures(this.m, this.handle);
  },

  /**
   * The achieved screen error in pixels of the current mesh for the current camera
   * (hexlod_lod_achieved_error_px); -1 in max-error mode.
   */
  achievedErrorPx() {
    return this.m._hexlod_lod_achieved_error_px(this.handle);
  },

  /** The mesh hash as 16 hexadecimal digits (high half first). */
  meshHash() {
    const m = this.m, h = this.handle;
    const hex = (half) => (half >>> 0).toString(16).padStart(8, '0');
    return hex(m._hexlod_mesh_hash_high(h)) + hex(m._hexlod_mesh_hash_low(h));
  },

  /**
   * Measures the mesh against the samples (a pass over every sample).
   * @param {boolean} againstStored true: the field the core stores (shifted rows interpolated
   *   for the shifted embedding); false: the original samples at their true positions
   * @returns {{max: number, p99: number, mean: number, uncovered: number}} metres, and samples
   */
  measureError(againstStored = false) {
    const [max, p99, mean, uncovered] = this.core.readOutput(Float64Array, 4, 'cannot measure the error',
      (out) => this.m._hexlod_mesh_measure_error(this.handle, againstStored ? 1 : 0, out));
    return { max, p99, mean, uncovered };
  },
});
