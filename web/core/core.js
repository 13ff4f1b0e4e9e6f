// The one JS module that owns the WebAssembly core (src/api/hexlod.h is the ABI it wraps; the
// diagnostics of src/api/hexlod_diagnostics.h exist only in the diagnostics build that Node
// loads, see lib/node_core.js). It runs unchanged in the browser, in workers and in Node; only
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
 * HEXLOD_ABI_VERSION of src/api/hexlod.h that this module was written for. A core of another
 * version (a stale build/, or a package whose .wasm and .js come from different builds) is
 * refused when it is instantiated, before any call whose arguments may have changed meaning.
 */
export const ABI_VERSION = 15;

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
    this.abiVersion = typeof module._hexlod_abi_version === 'function' ? module._hexlod_abi_version() : null;
    if (this.abiVersion !== ABI_VERSION) {
      const found = this.abiVersion === null ? 'exports no hexlod_abi_version' : `has ABI version ${this.abiVersion}`;
      throw new CoreError(`the WebAssembly core ${found}, but web/core/core.js needs ABI version ${ABI_VERSION}: rebuild the core (./build.sh wasm) or install a matching hexlod`);
    }
    this.layout = parseLayout(module.UTF8ToString(module._hexlod_struct_layout()));
    this.scratch = scratchLayout(this.layout);
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
    const scratch = this.module._malloc(this.scratch.bytes);
    if (scratch === 0) {
      this.module._hexlod_terrain_destroy(handle);
      throw new CoreError(`cannot create a ${width}x${height} ${sampleType} terrain: out of memory`);
    }
    return new Terrain(this, handle, width, height, sampleType, scratch);
  }

  /**
   * Creates a terrain whose samples arrive by tiles (hexlod_terrain_create_tiled), as a
   * Cloud-Optimized GeoTIFF read by range requests gives them: write and commit every tile of
   * the coarsest level (Terrain.tileBuffer, commitTile), then setScale, prepare and resetMesh.
   * @param {{width: number, height: number, tileWidth: number, tileHeight: number}[]} levels the
   *   full resolution first, then each overview, coarser each time (samples)
   * @param {'u8'|'u16'|'i16'|'f32'} sampleType native depth of the heights
   */
  createTiledTerrain(levels, sampleType) {
    const type = SAMPLE_TYPES[sampleType];
    if (!type) throw new CoreError(`unknown sample type '${sampleType}'`);
    const { width, height } = levels[0] ?? {};
    const dims = this.module._malloc(16 * Math.max(levels.length, 1));
    const scratch = this.module._malloc(this.scratch.bytes + 8); // + the tile wants' pointer
    if (dims === 0 || scratch === 0) {
      this.module._free(dims), this.module._free(scratch);
      throw new CoreError(`cannot create a ${width}x${height} ${sampleType} tiled terrain: out of memory`);
    }
    this.view(Int32Array, dims, 4 * levels.length).set(levels.flatMap((l) => [l.width, l.height, l.tileWidth, l.tileHeight]));
    const handle = this.module._hexlod_terrain_create_tiled(width, height, type.code, levels.length, dims);
    this.module._free(dims);
    if (handle === 0) this.module._free(scratch);
    this.check(handle === 0, `cannot create a ${width}x${height} ${sampleType} tiled terrain`);
    const terrain = new Terrain(this, handle, width, height, sampleType, scratch);
    terrain.levels = levels.map((l) => ({ ...l }));
    terrain.wantsSlot = (scratch >>> 0) + this.scratch.bytes;
    return terrain;
  }
}

/**
 * hexlod_struct_layout()'s text as {struct: {size, fields: {field: {offset, type, count}}}},
 * struct names without their hexlod_ prefix: every size and offset JS uses comes from here.
 */
export function parseLayout(text) {
  const structs = {};
  let struct = null;
  for (const line of text.split('\n')) {
    if (line === '') continue;
    const [name, offset, type, count] = line.trim().split(' ');
    if (line[0] !== ' ') structs[name.replace(/^hexlod_/, '')] = struct = { size: Number(offset), fields: {} };
    else struct.fields[name] = { offset: Number(offset), type, count: Number(count) };
  }
  return structs;
}

/** snake_case C names as camelCase JS names (tau_px -> tauPx). */
export const camelCase = (name) => name.replace(/_([a-z0-9])/g, (_, c) => c.toUpperCase());

// The structs of one terrain's calls in one block, allocated once: each struct at its byte
// offset (8-aligned), then one double for heights and up to 8 of a diagnostics call.
const SCRATCH_STRUCTS = ['frame', 'camera', 'settings', 'scale', 'field_info', 'level_view', 'mesh_settings'];
function scratchLayout(layout) {
  const offsets = {};
  let bytes = 0;
  for (const name of SCRATCH_STRUCTS) {
    offsets[name] = bytes;
    bytes += Math.ceil(layout[name].size / 8) * 8;
  }
  offsets.height = bytes;
  offsets.diagnostics = bytes + 8;
  offsets.bytes = bytes + 8 + 8 * 8;
  return offsets;
}

/**
 * Where one struct's fields lie in the Float64Array (f64) or Int32Array (i32, u32, ptr) over all
 * WASM memory, for a struct at byte address `base` (8-aligned): {field: element index}.
 */
function fieldIndices(struct, base) {
  const indices = {};
  for (const [name, { offset, type }] of Object.entries(struct.fields)) {
    indices[name] = (base + offset) / (type === 'f64' ? 8 : 4);
  }
  return indices;
}

/**
 * The figures of the last hexlod_terrain_frame call, one property per field of hexlod_frame in
 * camelCase (update_ms -> updateMs), but for FRAME_NAMES; pointers are byte offsets, already
 * `>>> 0`; converged is a boolean. Terrain.frame() copies them in, so this is the
 * same object every frame and a frame loop makes no garbage; read a figure before the next
 * frame call on the same terrain.
 */
export class FrameStats {
  /** The mesh hash as 16 hexadecimal digits (high half first; a string, so not per frame). */
  hash() {
    const hex = (half) => half.toString(16).padStart(8, '0');
    return hex(this.hashHigh) + hex(this.hashLow);
  }
}

// How each hexlod_frame field is read: 0 a double, 1 an int32, 2 unsigned (u32, pointers), 3 a flag.
const READ_F64 = 0, READ_I32 = 1, READ_U32 = 2, READ_FLAG = 3;
const FLAGS = new Set(['converged', 'refined']);
// hexlod_frame fields whose JS names are not plain camelCase (the names callers read).
const FRAME_NAMES = { tau_px: 'tau', vertices_ptr: 'vertexPointer', indices_ptr: 'indexPointer',
  dirty_vertices_ptr: 'dirtyVerticesPointer', dirty_indices_ptr: 'dirtyIndicesPointer', normals_ptr: 'normalsPointer' };

/** One height field in the core, and the mesh built from it. */
export class Terrain {
  constructor(core, handle, width, height, sampleType, scratch) {
    this.core = core;
    this.handle = handle;
    this.width = width;
    this.height = height;
    this.sampleType = sampleType;
    this.scratch = scratch >>> 0;
    this.f64View = null;
    this.i32View = null;
    this.hasMesh = false;
    const layout = core.layout, at = (name) => this.scratch + core.scratch[name];
    this.at = { frame: at('frame'), camera: at('camera'), settings: at('settings'), scale: at('scale'),
      fieldInfo: at('field_info'), levelView: at('level_view'), meshSettings: at('mesh_settings'),
      height: at('height'), diagnostics: at('diagnostics') };
    this.fields = {
      camera: fieldIndices(layout.camera, this.at.camera), settings: fieldIndices(layout.settings, this.at.settings),
      scale: fieldIndices(layout.scale, this.at.scale), fieldInfo: fieldIndices(layout.field_info, this.at.fieldInfo),
      levelView: fieldIndices(layout.level_view, this.at.levelView),
    };
    // hexlod_frame read field by field into this.stats: names, element indices and readers, made once.
    const frame = fieldIndices(layout.frame, this.at.frame);
    this.frameReads = Object.entries(layout.frame.fields).map(([name, { type }]) => ({
      key: FRAME_NAMES[name] ?? camelCase(name), index: frame[name],
      read: FLAGS.has(name) ? READ_FLAG : type === 'f64' ? READ_F64 : type === 'i32' ? READ_I32 : READ_U32,
    }));
    this.stats = new FrameStats();
    for (const { key } of this.frameReads) this.stats[key] = 0;
    // Every field of hexlod_settings as camelCase, 0 meaning the core's default (see configure).
    this.settings = {};
    for (const name of Object.keys(layout.settings.fields)) this.settings[camelCase(name)] = 0;
    this.levelViewOut = new LevelView(core);
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

  // --- A tiled terrain (createTiledTerrain) -----------------------------------------------------

  /** Whether the samples arrive by tiles. */
  get tiled() {
    return this.levels !== undefined;
  }

  /**
   * Where to write tile (tx, ty) of `level`: a fresh view of tileWidth x tileHeight samples, row
   * by row, valid until the next core call; commitTile once written.
   */
  tileBuffer(level, tx, ty) {
    const pointer = this.m._hexlod_terrain_tile_buffer(this.handle, level, tx, ty);
    this.core.check(pointer === 0, `no buffer for tile (${tx}, ${ty}) of level ${level}`);
    const { tileWidth, tileHeight } = this.levels[level];
    return this.core.view(SAMPLE_TYPES[this.sampleType].Array, pointer, tileWidth * tileHeight);
  }

  /** The tile's samples are written: the heights there come from it from the next frame on. */
  commitTile(level, tx, ty) {
    this.core.check(this.m._hexlod_terrain_commit_tile(this.handle, level, tx, ty) < 0, `cannot commit tile (${tx}, ${ty}) of level ${level}`);
  }

  /**
   * The bytes of samples the tiles past the coarsest level may hold (hexlod_terrain_set_tile_cap):
   * the core lets the least recently used go past it, never those the drawn mesh stands on.
   * query()'s tileBytes and tilesEvicted report it.
   */
  setTileCap(bytes) {
    this.core.check(this.m._hexlod_terrain_set_tile_cap(this.handle, bytes) < 0, `cannot set the tile cap to ${bytes} bytes`);
  }

  /**
   * How a tiled terrain fills its voids (hexlod_terrain_set_void_fill): with the lowest height
   * (`pits`, for drawing them as holes: the refinement follows their edges) or from the
   * surface around them.
   */
  setVoidsAsPits(pits) {
    this.core.check(this.m._hexlod_terrain_set_void_fill(this.handle, pits ? 1 : 0) < 0, 'cannot set the void fill');
  }

  /** The height range of all the samples, metres, as the file states it (hexlod_terrain_declare_height_range). */
  declareHeightRange(low, high) {
    this.core.check(this.m._hexlod_terrain_declare_height_range(this.handle, low, high) < 0, 'cannot declare the height range');
  }

  /**
   * The tiles the view waits for, most needed first (hexlod_terrain_tile_wants), into a list
   * reused from call to call: {level, tx, ty, priority (pixels)}.
   * @returns {{level: number, tx: number, ty: number, priority: number}[]}
   */
  tileWants() {
    const list = (this.wantList ??= []);
    return this.readTileList(list, this.m._hexlod_terrain_tile_wants(this.handle, this.wantsSlot), 'cannot collect the tiles to fetch');
  }

  /** Reads `count` hexlod_tile_want records the core pointed at into `list`. */
  readTileList(list, count, what) {
    this.core.check(count < 0, what);
    const layout = this.core.layout.tile_want, stride = layout.size / 4, f = layout.fields;
    const i32 = this.scratchI32(), f64 = this.scratchF64();
    const base = i32[this.wantsSlot >>> 2] >>> 0;
    for (let k = 0; k < count; k++) {
      const at = (base >>> 2) + k * stride;
      const want = (list[k] ??= { level: 0, tx: 0, ty: 0, priority: 0 });
      want.level = i32[at + f.level.offset / 4];
      want.tx = i32[at + f.tx.offset / 4];
      want.ty = i32[at + f.ty.offset / 4];
      want.priority = f64[(at + f.priority_px.offset / 4) >>> 1];
    }
    list.length = count;
    return list;
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
    const f = this.fields.scale, f64 = this.scratchF64(), i32 = this.scratchI32();
    f64[f.spacing_x_m] = spacingX;
    f64[f.spacing_y_m] = spacingY;
    f64[f.height_scale] = heightScale;
    f64[f.height_offset_m] = heightOffset;
    f64[f.nodata_raw] = hasNodata ? nodata : 0;
    i32[f.has_nodata] = hasNodata ? 1 : 0;
    i32[f.reserved] = 0;
    this.core.check(this.m._hexlod_terrain_set_scale(this.handle, this.at.scale) < 0, 'invalid height scale');
    this.spacingX = spacingX;
    this.spacingY = spacingY;
  }

  /** Fills missing samples and computes the height range; returns how many were missing. */
  prepare() {
    this.core.check(this.m._hexlod_terrain_prepare(this.handle, this.at.fieldInfo) < 0, 'cannot use this height field');
    const f = this.fields.fieldInfo, f64 = this.scratchF64();
    this.minHeight = f64[f.min_height_m];
    this.maxHeight = f64[f.max_height_m];
    return f64[f.missing];
  }

  /** Bilinear height in metres at (x, z) metres, clamped to the field. */
  heightAt(x, z) {
    return this.readHeight(x, z, 0);
  }

  /**
   * Height in metres (unscaled) of the surface as drawn now, geomorph blends included, at
   * (x, z) metres; NaN where nothing is drawn (outside the domain, or no mesh). After the
   * frame's stream step.
   */
  drawnHeightAt(x, z) {
    if (!this.hasMesh) return NaN;
    return this.readHeight(x, z, 1);
  }

  readHeight(x, z, surface) {
    const pointer = this.at.height;
    const covered = this.m._hexlod_terrain_height_at(this.handle, x, z, surface, pointer);
    this.core.check(covered < 0, 'cannot read a height');
    return covered === 1 ? this.scratchF64()[pointer / 8] : NaN;
  }

  // --- The hexagon mesh (paper §4) ---------------------------------------------------------------

  /**
   * (Re)creates the hexagon mesh over the whole field (paper §4.7); the settings are kept.
   * @param {'shifted'|'exact'} embedding the paper's shifted rows, or vertices on their samples
   */
  resetMesh(embedding = 'exact') {
    const code = EMBEDDINGS[embedding];
    if (code === undefined) throw new CoreError(`unknown embedding '${embedding}'`);
    const pointer = this.at.meshSettings;
    this.scratchI32()[(pointer + this.core.layout.mesh_settings.fields.embedding.offset) / 4] = code;
    this.core.check(this.m._hexlod_terrain_reset_mesh(this.handle, pointer) < 0, 'cannot create the hexagon mesh');
    this.hasMesh = true;
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
   * Returns the same LevelView object every call, valid until the next core call.
   */
  levelView(outline = false) {
    const pointer = this.at.levelView;
    const count = this.m._hexlod_terrain_level_view(this.handle, outline ? 1 : 0, pointer);
    this.core.check(count < 0, 'cannot build the level view');
    const i32 = this.scratchI32(), f = this.fields.levelView, out = this.levelViewOut;
    out.refresh();
    out.indexStart = (i32[f.indices] >>> 0) / 4;
    out.indexCount = i32[f.index_count];
    out.levelOffsetStart = (i32[f.level_offsets] >>> 0) / 4;
    out.levelOffsetCount = i32[f.level_offset_count];
    out.outlineStart = (i32[f.outline] >>> 0) / 4;
    out.outlineCount = i32[f.outline_count];
    return out;
  }

  // --- One frame (paper §5-§7) -------------------------------------------------------------------

  /**
   * One frame in one core call (hexlod_terrain_frame): the camera (null keeps the last one),
   * one LOD update within the budget, the stream. Returns this.stats, the same FrameStats
   * object every time, filled from hexlod_frame.
   * @param {{eye: ArrayLike<number>, target: ArrayLike<number>, up?: ArrayLike<number>, fovY?: number,
   *   tanHalfFovY?: number, aspect: number, viewportHeight: number, near: number, far: number}|null} camera
   *   eye and target in metres (x east, y up times the vertical scale, z south); up defaults
   *   to +y; fovY is the vertical field of view in radians, or give tanHalfFovY directly;
   *   aspect = viewport width / height; viewportHeight in device pixels; near, far in metres.
   * @param {number} [steps] FRAME bits: 0 all steps; FRAME.hash / FRAME.census add figures
   */
  frame(camera, steps = FRAME.all) {
    if (camera) this.writeCamera(camera);
    const result = this.m._hexlod_terrain_frame(this.handle, camera ? this.at.camera : 0, steps, this.at.frame);
    if (result < 0) {
      const message = this.core.lastError();
      throw new CoreError(`${message.startsWith('degenerate camera') ? 'invalid camera' : 'cannot run the frame'}: ${message}`);
    }
    this.readFrame();
    return this.stats;
  }

  /** Fills this.stats without changing anything (extra: FRAME.hash, FRAME.census). */
  query(extra = 0) {
    return this.frame(null, FRAME.query | extra);
  }

  // Copies hexlod_frame into this.stats, field by field (no allocation).
  readFrame() {
    const f64 = this.scratchF64(), i32 = this.scratchI32(), stats = this.stats, reads = this.frameReads;
    for (let k = 0; k < reads.length; k++) {
      const { key, index, read } = reads[k];
      if (read === READ_F64) stats[key] = f64[index];
      else if (read === READ_I32) stats[key] = i32[index];
      else if (read === READ_U32) stats[key] = i32[index] >>> 0;
      else stats[key] = i32[index] !== 0;
    }
  }

  // The camera into hexlod_camera. No up given: (0, 0, 0), which the core takes as +y.
  writeCamera({ eye, target, up, fovY, tanHalfFovY, aspect, viewportHeight, near, far }) {
    const f64 = this.scratchF64(), f = this.fields.camera;
    for (let c = 0; c < 3; c++) {
      f64[f.eye + c] = eye[c];
      f64[f.target + c] = target[c];
      f64[f.up + c] = up ? up[c] : 0;
    }
    f64[f.tan_half_fov_y] = tanHalfFovY ?? Math.tan(fovY / 2);
    f64[f.aspect] = aspect;
    f64[f.viewport_height_px] = viewportHeight;
    f64[f.near_m] = near;
    f64[f.far_m] = far;
  }

  /** Sets the camera of view-dependent refinement (a frame of FRAME.camera only; see frame()). */
  setLodCamera(camera) {
    this.frame(camera, FRAME.camera);
  }

  /** One refinement step within the budget; returns the number of operations it made. */
  updateLod() {
    return this.frame(null, FRAME.lod).operations;
  }

  /**
   * Applies the mesh's changes to the fan stream; call after updateLod.
   * @returns {number} the stream version: it moves whenever anything was written
   */
  updateStream() {
    return this.frame(null, FRAME.stream).version;
  }

  /**
   * Views on the fan stream, valid until the next core call (src/api/hexlod.h, hexlod_frame):
   * the vertex pool as bytes (STREAM_VERTEX_BYTES a slot) and as floats (STREAM_VERTEX_WORDS a
   * slot; the position comes first), the index array, and the ranges written since the last
   * acknowledgeStream() as [first, count] pairs of vertex slots and of indices. New views each
   * call: for tools; the renderer reads this.stats and one view on all memory instead.
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

  /**
   * Changes some settings in one core call (hexlod_terrain_set_settings), the rest kept. The
   * keys are hexlod_settings' fields in camelCase (see src/api/hexlod.h for units and ranges):
   * tauPx, maxErrorM (> 0: view-independent mode; 0: tau mode), verticalScale, budgetMs,
   * maxOperations, maxTriangles, autoTau, noFrustumCulling, noBackfaceCulling, morphFrames,
   * layout ('fans', 'triangles' or HEXLOD_LAYOUT_*), noNormals; flags take booleans. 0 means
   * the core's default, and every field starts at 0, so the defaults are the core's own. On a
   * refusal the previous settings stay, here and in the core, and a CoreError says why.
   * @param {object} change
   */
  configure(change) {
    for (const key of Object.keys(change)) {
      if (!(key in this.settings)) {
        throw new TypeError(`unknown core setting '${key}' (expected one of ${Object.keys(this.settings).join(', ')})`);
      }
    }
    if (change.layout !== undefined && typeof change.layout === 'string' && STREAM_LAYOUTS[change.layout] === undefined) {
      throw new TypeError(`unknown stream layout ${change.layout} (expected fans or triangles)`);
    }
    const next = { ...this.settings, ...change };
    const f64 = this.scratchF64(), i32 = this.scratchI32(), fields = this.core.layout.settings.fields;
    for (const [name, { type }] of Object.entries(fields)) {
      const value = next[camelCase(name)];
      const index = (this.at.settings + fields[name].offset) / (type === 'f64' ? 8 : 4);
      if (type === 'f64') f64[index] = value;
      else i32[index] = typeof value === 'string' ? STREAM_LAYOUTS[value] : Number(value);
    }
    this.core.check(this.m._hexlod_terrain_set_settings(this.handle, this.at.settings) < 0, 'invalid settings');
    this.settings = next;
  }

  /**
   * The surface the terrain is drawn on (hexlod_terrain_set_earth; web/geo/earth_shape.js makes
   * the shape): the refinement's bound follows its curvature. Kept across configure().
   * @param {{kind: number, originX: number, originZ: number, radius: number, latitude0: number,
   *   metresPerRadianX: number, metresPerRadianZ: number}} earth
   */
  setEarth(earth) {
    const e = earth;
    this.core.check(this.m._hexlod_terrain_set_earth(this.handle, e.kind, e.originX, e.originZ, e.radius, e.latitude0,
      e.metresPerRadianX, e.metresPerRadianZ) < 0, 'invalid earth shape');
  }

  // --- Diagnostics (src/api/hexlod_diagnostics.h: the diagnostics build only, e.g. in Node) -------

  /** The diagnostics function `name`, or a CoreError saying which build has it. */
  diagnostic(name) {
    const fn = this.m[`_hexlod_diag_${name}`];
    if (typeof fn !== 'function') {
      throw new CoreError(`${name} is a diagnostic: load the diagnostics build (build/wasm-diag, lib/node_core.js)`);
    }
    return fn;
  }

  /** Calls a diagnostics function that writes `length` doubles; returns them as an array. */
  readDiagnostic(name, length, what, ...args) {
    const pointer = this.at.diagnostics;
    this.core.check(this.diagnostic(name)(this.handle, ...args, pointer) < 0, what);
    return Array.from(this.scratchF64().subarray(pointer / 8, pointer / 8 + length));
  }

  /**
   * The settings in force with every default resolved (hexlod_diag_settings), keyed as
   * configure() takes them: the core's defaults, for tests.
   */
  settingsInForce() {
    this.core.check(this.diagnostic('settings')(this.handle, this.at.settings) < 0, 'cannot read the settings');
    const f64 = this.scratchF64(), i32 = this.scratchI32(), fields = this.core.layout.settings.fields, out = {};
    for (const [name, { offset, type }] of Object.entries(fields)) {
      const address = this.at.settings + offset;
      out[camelCase(name)] = type === 'f64' ? f64[address / 8] : i32[address / 4];
    }
    return out;
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
   * Checks that the stream draws one watertight surface (hexlod_diag_check_stream): throws with
   * the first defect, else {triangles, vertices, edges, boundaryEdges, loops, euler, indices}.
   */
  checkStream() {
    const [triangles, vertices, edges, boundaryEdges, loops, euler, indices] = this.readDiagnostic('check_stream', 7, 'the stream is not watertight');
    return { triangles, vertices, edges, boundaryEdges, loops, euler, indices };
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

/**
 * The level-ordered view (Terrain.levelView): where its arrays lie in WASM memory, as element
 * indices into `u32` / `i32` (views on all memory, made again only after it grew), so that a
 * frame with colour by level on makes no new view. The getters make views, for tools.
 */
export class LevelView {
  constructor(core) {
    this.core = core;
    this.u32 = null;
    this.i32 = null;
    this.indexStart = 0;
    this.indexCount = 0;
    this.levelOffsetStart = 0;
    this.levelOffsetCount = 0;
    this.outlineStart = 0;
    this.outlineCount = 0;
  }

  refresh() {
    const buffer = this.core.buffer;
    if (this.u32 === null || this.u32.buffer !== buffer) {
      this.u32 = new Uint32Array(buffer);
      this.i32 = new Int32Array(buffer);
    }
  }

  get indices() { return this.u32.subarray(this.indexStart, this.indexStart + this.indexCount); }
  get levelOffsets() { return this.i32.subarray(this.levelOffsetStart, this.levelOffsetStart + this.levelOffsetCount); }
  get outline() { return this.u32.subarray(this.outlineStart, this.outlineStart + this.outlineCount); }
}
