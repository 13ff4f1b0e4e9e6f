/* hexlod.h: the product C ABI of the hexlod core, what the page and every other caller use
 * (JS through WebAssembly, native tests and benchmarks). Every name has the prefix hexlod_.
 * Measurements for tests and benchmarks are in hexlod_diagnostics.h, exported only by the
 * diagnostics builds.
 *
 * Conventions
 * - Errors, one rule: a function that can fail returns a negative int32 status
 *   (HEXLOD_ERROR) or NULL, and hexlod_last_error() then says what was wrong in one sentence.
 *   Zero or a positive count means success; no function signals failure with 0.0, NaN or an
 *   unset message. Misuse (a NULL handle, a NULL struct that is required) fails the same way.
 * - Settings come in structs where zero means default: clear the struct (`= {0}`), set what
 *   you need. Out structs are filled by the call; the pointers in them stay valid until the
 *   next call on the same terrain (or until memory grows, for JS views).
 * - Units: horizontal positions and spacings in metres, x east from the first column, z south
 *   from the first row, y up; heights in metres after the height scale and offset.
 * - A terrain handle owns its samples and the mesh built from them.
 * - Under WebAssembly, pointers are byte offsets into the module's memory; Emscripten 3.1.6
 *   hands them to JS as signed 32-bit numbers: read them as `ptr >>> 0`. The struct layouts
 *   below are the wasm32 ones JS reads; JS takes every size and offset from
 *   hexlod_struct_layout(), never from a copy of its own.
 * - A frame (hexlod_terrain_frame) allocates nothing unless the mesh's pools grow.
 */
#ifndef HEXLOD_H
#define HEXLOD_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a signature, a struct layout or a meaning below changes. */
#define HEXLOD_ABI_VERSION 15

/* The status of every failure. */
#define HEXLOD_ERROR (-1)

/* Sample types: the native depth of the file's heights. */
#define HEXLOD_SAMPLE_U8 1
#define HEXLOD_SAMPLE_U16 2
#define HEXLOD_SAMPLE_I16 3
#define HEXLOD_SAMPLE_F32 4

/* Lattice embeddings (§4.7): every vertex on its sample (the default), or the paper's odd rows
 * shifted half a sample east with interpolated heights. */
#define HEXLOD_EMBEDDING_EXACT 0
#define HEXLOD_EMBEDDING_SHIFTED 1

/* Index layouts of the stream (§7), see hexlod_frame. */
#define HEXLOD_LAYOUT_FANS 0
#define HEXLOD_LAYOUT_TRIANGLES 1

typedef struct hexlod_terrain hexlod_terrain;

/* How samples become metres. 48 bytes. */
typedef struct hexlod_scale {
    double spacing_x_m;     /* between columns, 1e-6 to 1e8 (0: 1 m) */
    double spacing_y_m;     /* between rows, 1e-6 to 1e8 (0: 1 m) */
    double height_scale;    /* height_m = raw * height_scale + height_offset_m; negative flips; |.| at most 1e9 (0: 1) */
    double height_offset_m; /* -1e9 to 1e9 */
    double nodata_raw;      /* with has_nodata, samples equal to this are missing (NaN and infinities always are) */
    int32_t has_nodata;
    int32_t reserved;       /* 0 */
} hexlod_scale;

/* What hexlod_terrain_prepare found. 32 bytes. */
typedef struct hexlod_field_info {
    double min_height_m, max_height_m; /* the height range of the valid samples */
    double missing;                    /* missing samples, filled (the lowest valid height; a tiled field: hexlod_terrain_set_void_fill) */
    double sample_bytes;               /* the size of the sample array */
} hexlod_field_info;

/* The mesh's construction. 4 bytes. */
typedef struct hexlod_mesh_settings {
    int32_t embedding; /* HEXLOD_EMBEDDING_* (0: exact) */
} hexlod_mesh_settings;

/* Refinement (§5, §6), blends and stream (§7): everything but the camera. 64 bytes.
 * Once converged, every sample in the view frustum is within tau pixels of the drawn surface on
 * screen, or, with max_error_m > 0, every sample of the field within max_error_m metres.
 * The ranges are what hexlod_terrain_set_settings accepts; NaN and infinities never are. */
typedef struct hexlod_settings {
    double tau_px;               /* screen-space tolerance in device pixels, 0.01 to 10000 (0: 1) */
    double max_error_m;          /* 1e-6 to 1e9: view-independent mode, the camera ignored (0: tau mode) */
    double vertical_scale;       /* heights are drawn times this, 0.001 to 1000 (0: 1) */
    double budget_ms;            /* time per LOD update, up to 60000 (0: no limit) */
    int32_t max_operations;      /* splits and merges per LOD update, >= 0 (0: no limit); every update makes progress */
    int32_t max_triangles;       /* no split starts while more are drawn (one that started finishes the splits
                                    the balance rule needs first, so the count may pass the cap by those), >= 0 (0: no cap) */
    int32_t auto_tau;            /* non-zero: tau rises while the cap or the time budget is exceeded and falls back (§6) */
    int32_t no_frustum_culling;  /* non-zero: cells outside the view are refined as inside */
    int32_t no_backface_culling; /* non-zero: no cone-of-normals culling (exact embedding, cells of up to 4096 samples) */
    int32_t morph_frames;        /* geomorph blend length in LOD updates, at most 1000 (0: off) */
    int32_t layout;              /* HEXLOD_LAYOUT_* (0: fans) */
    int32_t no_normals;          /* non-zero: the stream keeps no vertex normals (32 bytes a vertex saved) */
} hexlod_settings;

/* The camera of view-dependent refinement. 112 bytes. The caller computes the tangent, so no
 * transcendental function enters a split decision. The ranges are what hexlod_terrain_frame
 * accepts; NaN and infinities never are. */
typedef struct hexlod_camera {
    double eye[3];             /* metres, world frame (x east, y up, z south; heights times the vertical
                                  scale), each -1e12 to 1e12 */
    double target[3];          /* metres, a point looked at, each -1e12 to 1e12, at least 1e-6 from eye */
    double up[3];              /* (0, 0, 0): +y; else at least 1e-6 long, each at most 1e12, and off the
                                  view direction (sine of the angle at least 1e-6): looking straight up
                                  or down, give e.g. (0, 0, -1) */
    double tan_half_fov_y;     /* tan(vertical field of view / 2), 1e-4 to 1e4 (0.0115 to 179.989 degrees) */
    double aspect;             /* viewport width / height, 1e-4 to 1e4 */
    double viewport_height_px; /* device pixels, 1 to 100000 */
    double near_m, far_m;      /* clip plane distances: 1e-6 <= near_m < far_m <= 1e12 */
} hexlod_camera;

/* Steps of hexlod_terrain_frame (bits; 0 = HEXLOD_FRAME_ALL). */
#define HEXLOD_FRAME_ALL 0     /* the camera (when given), one LOD update, the stream */
#define HEXLOD_FRAME_CAMERA 1  /* only the steps whose bits are set */
#define HEXLOD_FRAME_LOD 2
#define HEXLOD_FRAME_STREAM 4
#define HEXLOD_FRAME_QUERY 8   /* no step: only fill the output */
#define HEXLOD_FRAME_HASH 16   /* also the mesh hash (a pass over the cells) */
#define HEXLOD_FRAME_CENSUS 32 /* also the cell kinds and the achieved screen error (passes over the cells) */

/* One frame's output. 192 bytes under wasm32: 6 doubles, 31 int32, 5 pointers.
 *
 * The stream (§7), what the renderer uploads, kept in step with the mesh:
 * Vertices: the mesh's own vertex pool (vertex data exists once), 20 bytes a slot:
 *   bytes  0..11  position, 3 float32, metres (y unscaled: the shader multiplies heights by the
 *                 vertical exaggeration)
 *   bytes 12..15  morph start height, float32, metres (unscaled): the height of the coarser
 *                 surface under the vertex, where the blend starts (blends are vertical)
 *   bytes 16..19  morph key, float32: 0 at rest; f+1 blending in since frame f; -(f+1)
 *                 blending out since frame f. With n = morph_frames and F = frame, the drawn
 *                 position is (x, mix(morph start height, y, w), z), t = clamp((F - f) / n, 0, 1),
 *                 w = t blending in, 1 - t blending out, 1 at rest or when n = 0.
 * Free slots hold stale data and are never indexed.
 * Normals (NULL with no_normals): one per vertex slot, 8 bytes, 4 snorm16 (x, y, z, m), averaged
 * from the adjacent triangles (§7); m is 1 where the vertex's height fills a no-data sample of a
 * tiled field (else 0). They change with the same dirty vertex ranges.
 * Indices: a fixed slot per cell record: HEXLOD_LAYOUT_FANS, 9 indices (a triangle fan then
 * 0xFFFFFFFF; full hexagon: centre, six corners, first corner; boundary semi-hexagon: centre,
 * four corners; interior semi-hexagon: four corners from the fixed-rule corner; the rest of the
 * slot and free records: 0xFFFFFFFF), drawn as TRIANGLE_FAN with primitive restart (this is the
 * mesh's own table of cell vertices, so its pointer moves with the cell pool); or
 * HEXLOD_LAYOUT_TRIANGLES, 18 indices (the same triangles as a list, padded with 0xFFFFFFFF).
 * Dirty ranges: what changed since the last hexlod_terrain_acknowledge, as (first, count) pairs
 * of int32: vertex slots and indices. */
typedef struct hexlod_frame {
    /* doubles: Float64Array index 0..6 */
    double update_ms;         /* the last LOD update's milliseconds */
    double tau_px;            /* the tau in use (auto tau may have raised it) */
    double frame;             /* the blends' clock, one tick per LOD update: the shader's F */
    double memory_bytes;      /* mesh structures, the refiner's caches and the stream */
    double triangles;         /* drawn triangles */
    double achieved_error_px; /* HEXLOD_FRAME_CENSUS: the largest projected-error bound (§5) over the
                                 cells in view whose bound is cached; at most tau once converged;
                                 -1 in max-error mode. Else kept from the last census. */
    double tile_bytes;        /* a tiled terrain: bytes of samples held in tiles past the coarsest
                                 level (see hexlod_terrain_set_tile_cap); 0 for one held whole */
    /* int32: Int32Array index 14..42 */
    int32_t version;          /* the stream's version: it moves whenever anything was written */
    int32_t converged;        /* 1: the last update tested every due cell, resolved every failing test,
                                 and no merge waits for a fade-out */
    int32_t operations;       /* the last LOD update's steps (splits, joins, merges, breaks; forced ones too) */
    int32_t splits, merges;   /* of the last LOD update, forced ones included */
    int32_t cells_tested;     /* criteria evaluations (§5) of the last LOD update */
    int32_t pending_merges;   /* merges waiting for their vertices to fade out */
    int32_t cells, vertices;  /* live cells and vertices */
    int32_t max_level;        /* the finest level a cell can reach */
    int32_t full_hexagons, semi_hexagons, boundary_semi_hexagons; /* HEXLOD_FRAME_CENSUS (§4.2), else kept */
    uint32_t hash_low, hash_high; /* HEXLOD_FRAME_HASH: the mesh hash (cells, levels, lattice points, positions), else kept */
    int32_t vertex_count;     /* vertex slots (the pool's capacity) */
    int32_t index_count;      /* indices */
    int32_t dirty_vertex_pairs, dirty_index_pairs; /* pairs in the dirty arrays */
    int32_t refined;          /* 1: the last update tested every due cell and resolved every failing
                                 test, so the mesh is within tau; merges may still wait for fades */
    int32_t tiles_evicted;    /* a tiled terrain: tiles it let go so far to stay within its tile cap */
    int32_t reserved[8];
    /* pointers: Int32Array index 43..47 under wasm32 */
    const void* vertices_ptr;         /* the vertex pool */
    const uint32_t* indices_ptr;      /* the index array */
    const int32_t* dirty_vertices_ptr; /* (first, count) pairs of vertex slots */
    const int32_t* dirty_indices_ptr;  /* (first, count) pairs of indices */
    const int16_t* normals_ptr;        /* the vertex normals, or NULL with no_normals */
} hexlod_frame;

/* The level-ordered view for diagnostics of the page (colour by level, hexagon outlines). */
typedef struct hexlod_level_view {
    const uint32_t* indices;      /* every cell's fan closed by 0xFFFFFFFF, grouped by level */
    const int32_t* level_offsets; /* first index of each level 0..max_level, then the length */
    const uint32_t* outline;      /* with outline: every cell edge once, as line pairs */
    int32_t index_count, level_offset_count, outline_count;
} hexlod_level_view;

/* Heights hexlod_terrain_height_at can read. */
#define HEXLOD_SURFACE_FIELD 0 /* the samples, bilinear, clamped to the field */
#define HEXLOD_SURFACE_DRAWN 1 /* the surface as drawn now: the stream's triangles, blends included */

/* One tile a tiled terrain should fetch next. 24 bytes. */
typedef struct hexlod_tile_want {
    int32_t level;       /* 0: the full resolution; each next level coarser (as given at creation) */
    int32_t tx, ty;      /* the tile's column (0 at the west) and row (0 at the north) in its level */
    int32_t reserved;
    double priority_px;  /* the largest projected error (device pixels; metres in max-error mode) of a
                            cell that waits for it: fetch the largest first */
} hexlod_tile_want;
/* Returns HEXLOD_ABI_VERSION of the compiled core. */
uint32_t hexlod_abi_version(void);

/* The byte layout of the structs above as this build compiled them, for callers that read and
 * write them through views on memory (JS): text in static storage, never NULL; it cannot fail.
 * One line a struct, "<struct> <size in bytes>", followed by one line a field, indented by a
 * space: "<field> <byte offset> <type> <count>", type f64, i32, u32 or ptr (a pointer: 4 bytes
 * under wasm32), count the array length (1 for a scalar). Reserved fields are left out. */
const char* hexlod_struct_layout(void);

/* The message of the last failure in this thread (static storage, never NULL; empty when
 * nothing failed yet). */
const char* hexlod_last_error(void);

/* Creates a terrain of width x height samples (each 2..65536) of a HEXLOD_SAMPLE_* type, with
 * uninitialised samples. NULL for a bad size or type or when memory is exhausted. */
hexlod_terrain* hexlod_terrain_create(int32_t width, int32_t height, int32_t sample_type);

/* Frees the terrain and everything built from it. NULL is ignored. */
void hexlod_terrain_destroy(hexlod_terrain* terrain);

/* Where the caller writes the samples: width*height values of the sample type, row-major,
 * row 0 north, native byte order. NULL on failure. */
void* hexlod_terrain_samples(hexlod_terrain* terrain);

/* A terrain whose samples arrive by tiles, as a Cloud-Optimized GeoTIFF read by range requests
 * gives them: level_count levels (1 to 24), dims = level_count x (width, height, tile_width,
 * tile_height), the full resolution first (width x height samples, each side 2..2097152: a world
 * DEM at 1 arc-second is 1296000 x 626400; its memory follows the tiles held, not its size), each
 * next level coarser (an overview; its sample k lies at full-resolution position
 * (k + 0.5) * width / level_width - 0.5), tiles of 1 to 4096 samples a side and at most 2^26
 * tiles a level. It holds no sample yet: write and commit every tile
 * of the coarsest level, then hexlod_terrain_set_scale, hexlod_terrain_prepare and
 * hexlod_terrain_reset_mesh as for any terrain. Heights come from the finest level present
 * (bilinear between its samples); the refinement splits no cell finer than that level and asks
 * for the tiles it needs instead (hexlod_terrain_tile_wants). hexlod_terrain_samples has no
 * array to give for it. NULL on failure. */
hexlod_terrain* hexlod_terrain_create_tiled(int32_t width, int32_t height, int32_t sample_type, int32_t level_count,
                                            const int32_t* dims);
/* Where to write tile (tx, ty) of `level` of a tiled terrain: tile_width x tile_height samples of
 * its sample type, row by row (what lies past the level's edge is ignored). The same buffer until
 * the tile is evicted. NULL outside the levels, for a terrain held whole, or out of memory. */
void* hexlod_terrain_tile_buffer(hexlod_terrain* terrain, int32_t level, int32_t tx, int32_t ty);
/* The tile's samples are written. Its missing samples (nodata, NaN) are filled as
 * hexlod_terrain_set_void_fill says; the heights there come from it at the end of the next frame's stream step, where the vertices blend
 * to them (§7) and the cells are tested again. 0, or HEXLOD_ERROR for a tile with no buffer. */
int32_t hexlod_terrain_commit_tile(hexlod_terrain* terrain, int32_t level, int32_t tx, int32_t ty);
/* The bytes of samples a tiled terrain may hold in tiles past its coarsest level (which is held
 * whole and not counted); unlimited until set. The terrain owns its tiles: at each frame's stream
 * step that finds them over the cap, it lets the least recently used go (their heights fall back
 * to a coarser level, the vertices blending there as for a commit), never one the drawn mesh
 * stands on, so the tiles in use alone may exceed it. A tile let go is wanted again
 * (hexlod_terrain_tile_wants) when the view needs it. hexlod_frame's tile_bytes and
 * tiles_evicted report it. 0, or HEXLOD_ERROR for a terrain held whole or a cap that is not a
 * number >= 0. */
int32_t hexlod_terrain_set_tile_cap(hexlod_terrain* terrain, double cap_bytes);
/* How a tiled terrain fills its missing samples (nodata, NaN), in the tiles present and those to come:
 * HEXLOD_VOIDS_SURFACE (the default) from the surface around them, the coarsest level by linear
 * interpolation across each gap along rows and columns (their mean; the lowest height where
 * neither has data) and every finer tile from the coarser level under it; or
 * HEXLOD_VOIDS_LOWEST with the lowest height, whose walls make the refinement follow a void's
 * edge to the data's resolution (for drawing voids as holes: see the normals' m). The heights
 * change at the next frame's stream step, blending as for a commit. 0, or HEXLOD_ERROR for a
 * terrain held whole (its caller fills it) or another value. */
#define HEXLOD_VOIDS_SURFACE 0
#define HEXLOD_VOIDS_LOWEST 1
int32_t hexlod_terrain_set_void_fill(hexlod_terrain* terrain, int32_t fill);
/* The height range (metres) of all the samples of a tiled terrain, when the file states it
 * (GDAL's STATISTICS_MINIMUM and STATISTICS_MAXIMUM): the tiles present cannot show it. The
 * refinement's cached bounds are packed in steps of the height range, so with the whole range
 * declared the mesh converges to the one of the same field loaded whole; without it, to one
 * just as close to the samples (tau holds either way). Call after hexlod_terrain_prepare; the
 * range only widens. 0, or HEXLOD_ERROR for a terrain held whole or a bad range. */
int32_t hexlod_terrain_declare_height_range(hexlod_terrain* terrain, double low_m, double high_m);
/* The tiles the current view waits for, most needed first, at most 4096: those of the level the
 * children of every cell held back by the data need (a cell whose test with the detail its
 * level's samples show fails, while its children would be finer than that level). Collected
 * anew at each call from the last LOD update, so a tile no cell needs any more drops out.
 * *wants points at them until the next call on the terrain. Returns their count (0 for a
 * terrain held whole), or HEXLOD_ERROR without a mesh. */
int32_t hexlod_terrain_tile_wants(hexlod_terrain* terrain, const hexlod_tile_want** wants);

/* Sets how samples become metres. With a mesh, the mesh is rebuilt from its base for the new
 * scale (positions and cached refinement data change; settings are kept). 0 or HEXLOD_ERROR,
 * the previous scale and mesh kept: a non-finite field, a spacing outside 1e-6..1e8 m, a height
 * scale of magnitude over 1e9, an offset outside -1e9..1e9 m, or, with a mesh, heights the new
 * scale puts outside -1e9..1e9 m (see hexlod_terrain_prepare). */
int32_t hexlod_terrain_set_scale(hexlod_terrain* terrain, const hexlod_scale* scale);

/* Call once the samples are written (and after any change to them): fills missing samples with
 * the lowest valid height, computes the height range and fills *info (may be NULL).
 * 0 or HEXLOD_ERROR, nothing changed: every sample missing, or a valid sample whose height
 * (raw * height_scale + height_offset_m) lies outside -1e9..1e9 m, most often an undeclared
 * nodata value. */
int32_t hexlod_terrain_prepare(hexlod_terrain* terrain, hexlod_field_info* info);

/* (Re)creates the base hexagon mesh over the whole field (§4.7); settings (NULL: defaults)
 * choose the embedding. 0 or HEXLOD_ERROR. */
int32_t hexlod_terrain_reset_mesh(hexlod_terrain* terrain, const hexlod_mesh_settings* settings);

/* Sets everything but the camera (NULL: defaults). A change that decides splits re-tests every
 * cell at the next update; a layout or normals change rewrites the stream. Works before the
 * mesh exists and is kept across mesh resets. 0 or HEXLOD_ERROR, the previous settings kept,
 * the message naming the field and its range: a field outside the range its comment in
 * hexlod_settings gives (NaN, infinities, negative numbers included), morph frames outside
 * 0..1000, an unknown layout. The flags (auto_tau, no_*) take any int32, non-zero meaning set. */
int32_t hexlod_terrain_set_settings(hexlod_terrain* terrain, const hexlod_settings* settings);

/* The surface the terrain is drawn on (src/lod/earth_shape.h): the refinement's bound (§5)
 * follows its curvature, so tau holds on the curved surface as drawn. The drawn frame is east,
 * up and south metres of a tangent frame whose origin is the flat point (origin_x_m, 0,
 * origin_z_m); the renderer draws vertices as shaders/earth.glsl does, with the same numbers.
 *   HEXLOD_EARTH_FLAT: the plane (the default); the other numbers are ignored.
 *   HEXLOD_EARTH_SPHERE: the plane wrapped onto a sphere of radius_m (1e3 to 1e9), keeping
 *     distances and directions from the origin.
 *   HEXLOD_EARTH_GEOGRAPHIC: flat x is longitude and z latitude (southwards) at fixed steps,
 *     metres_per_radian_x and _z of them (each 1 to 1e12), the origin at latitude0_rad
 *     (-pi/2 to pi/2); drawn on the WGS 84 ellipsoid.
 * Kept across hexlod_terrain_set_settings. The origin's coordinates are within -1e12 to 1e12.
 * A change makes every cell due for a new test. 0, or HEXLOD_ERROR (the previous shape stays). */
#define HEXLOD_EARTH_FLAT 0
#define HEXLOD_EARTH_SPHERE 1
#define HEXLOD_EARTH_GEOGRAPHIC 2
int32_t hexlod_terrain_set_earth(hexlod_terrain* terrain, int32_t kind, double origin_x_m, double origin_z_m, double radius_m,
                                 double latitude0_rad, double metres_per_radian_x, double metres_per_radian_z);

/* One frame, the steps chosen by `steps` (HEXLOD_FRAME_*): the camera (NULL keeps the last
 * one), one refinement step within the budget (§6: re-test the cells whose margin the camera
 * used up, refine the failing ones largest projected error first, coarsen in descending level
 * order; the mesh is consistent after every operation), then the stream (§7: only what changed
 * is rewritten). Fills *out (required). 0 or HEXLOD_ERROR: no mesh, unknown step bits, or a
 * camera field outside the range its comment in hexlod_camera gives (NaN, infinities, zero or
 * negative sizes and planes, near_m >= far_m, eye on the target, up along the view). A refused
 * camera fails the whole call, the message starting "degenerate camera: " and naming the field:
 * no step runs, and the previous camera, mesh and stream stay. */
int32_t hexlod_terrain_frame(hexlod_terrain* terrain, const hexlod_camera* camera, int32_t steps, hexlod_frame* out);

/* The renderer uploaded every dirty range: forget them. 0 or HEXLOD_ERROR. */
int32_t hexlod_terrain_acknowledge(hexlod_terrain* terrain);

/* Height in metres at ground position (x_m, z_m) of a HEXLOD_SURFACE_*, written to *height_m.
 * The drawn surface is unscaled (times the vertical scale on screen) and the highest where
 * triangles meet; call it after the frame's stream step; it scans every cell (about a
 * millisecond for 100k triangles). Returns 1, 0 where no drawn triangle covers the point
 * (outside the domain, or a NaN or infinite position; *height_m = NaN), or HEXLOD_ERROR. */
int32_t hexlod_terrain_height_at(const hexlod_terrain* terrain, double x_m, double z_m, int32_t surface, double* height_m);

/* Writes the level-ordered view (not incrementally; outline non-zero adds the cell edges) and
 * fills *out (required). Returns its index count, or HEXLOD_ERROR. */
int32_t hexlod_terrain_level_view(hexlod_terrain* terrain, int32_t outline, hexlod_level_view* out);

#ifdef __cplusplus
}
#endif

#endif /* HEXLOD_H */
