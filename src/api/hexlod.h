/* hexlod.h: the whole C ABI between the hexlod core and its callers (JS through WebAssembly,
 * native tests and benchmarks). Every function has the prefix hexlod_.
 *
 * Conventions
 * - Units: horizontal positions and spacings in metres, x east from the first column, z south
 *   from the first row, y up; heights in metres after the height scale and offset.
 * - A terrain handle owns its samples and every mesh built from it. Arrays returned by the
 *   core stay valid until the next call that rebuilds them or until the terrain is destroyed.
 * - Functions that can fail return a negative number or NULL; hexlod_last_error() then says
 *   what was wrong in one sentence. Misuse (a NULL handle) is reported the same way.
 * - Under WebAssembly, pointers are byte offsets into the module's memory. Emscripten 3.1.6
 *   hands them to JS as signed 32-bit numbers: read them as `ptr >>> 0`.
 */
#ifndef HEXLOD_H
#define HEXLOD_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a signature or a meaning below changes. */
#define HEXLOD_ABI_VERSION 8

/* Sample types: the native depth of the file's heights. */
#define HEXLOD_SAMPLE_U8 1
#define HEXLOD_SAMPLE_U16 2
#define HEXLOD_SAMPLE_I16 3
#define HEXLOD_SAMPLE_F32 4

typedef struct hexlod_terrain hexlod_terrain;

/* Returns HEXLOD_ABI_VERSION of the compiled core. */
uint32_t hexlod_abi_version(void);

/* Returns the message of the last failure in this thread (static storage, never NULL; empty
 * when nothing failed yet). */
const char* hexlod_last_error(void);

/* Creates a terrain of width x height samples (each at least 2, at most 65536) of the given
 * HEXLOD_SAMPLE_* type, with uninitialised samples. Returns NULL when the size or type is
 * invalid or memory is exhausted. */
hexlod_terrain* hexlod_terrain_create(int32_t width, int32_t height, int32_t sample_type);

/* Frees the terrain and everything built from it. NULL is ignored. */
void hexlod_terrain_destroy(hexlod_terrain* terrain);

/* Returns where the caller writes the samples: width*height values of the sample type,
 * row-major, row 0 north, native byte order. */
void* hexlod_terrain_samples(hexlod_terrain* terrain);

/* Returns the size in bytes of the sample array. */
double hexlod_terrain_sample_bytes(const hexlod_terrain* terrain);

/* Sets how samples become metres: spacing_x_m and spacing_y_m between columns and rows
 * (metres, > 0), height_m = raw * height_scale + height_offset_m. When has_nodata is non-zero,
 * samples equal to nodata_raw are missing (NaN and infinities always are). If the terrain has
 * a hexagon mesh, it is rebuilt from its base mesh for the new scale (positions and cached
 * refinement data change; LOD settings are kept).
 * Returns 0, or -1 for a non-finite or non-positive spacing or a zero scale. */
int32_t hexlod_terrain_set_scale(hexlod_terrain* terrain, double spacing_x_m, double spacing_y_m,
                                 double height_scale, double height_offset_m, int32_t has_nodata,
                                 double nodata_raw);

/* Call once the samples are written (and after any change to them): fills missing samples
 * with the lowest valid height and computes the height range. Returns the number of missing
 * samples that were filled (>= 0), or -1 when every sample is missing. */
double hexlod_terrain_prepare(hexlod_terrain* terrain);

/* Lowest and highest height in metres, valid after hexlod_terrain_prepare. */
double hexlod_terrain_min_height(const hexlod_terrain* terrain);
double hexlod_terrain_max_height(const hexlod_terrain* terrain);

/* Bilinear height in metres at (x_m, z_m), clamped to the field. */
double hexlod_terrain_height_at(const hexlod_terrain* terrain, double x_m, double z_m);

/* --- The hexagon mesh (paper §4) ------------------------------------------------------------
 * One hexagon mesh per terrain. Embeddings: HEXLOD_EMBEDDING_SHIFTED (the paper's: odd rows
 * half a sample east, heights interpolated) or HEXLOD_EMBEDDING_EXACT (every vertex on its
 * sample). */
#define HEXLOD_EMBEDDING_SHIFTED 0
#define HEXLOD_EMBEDDING_EXACT 1

/* (Re)creates the base mesh over the whole field. Returns 0, or -1 for a bad embedding. */
int32_t hexlod_mesh_reset(hexlod_terrain* terrain, int32_t embedding);

/* Splits every whole cell of the coarsest levels, `rounds` times: the uniform split, equal to
 * that many 1-to-4 splits of the base triangulation. Returns the number of splits, or -1. */
int32_t hexlod_mesh_refine_uniform(hexlod_terrain* terrain, int32_t rounds);

/* Finest level a cell can reach (2 * number of resolutions below the base). */
int32_t hexlod_mesh_max_level(const hexlod_terrain* terrain);
/* Triangles drawn, live cells, live vertices of the mesh. */
int32_t hexlod_mesh_triangle_count(const hexlod_terrain* terrain);
int32_t hexlod_mesh_cell_count(const hexlod_terrain* terrain);
int32_t hexlod_mesh_vertex_count(const hexlod_terrain* terrain);
/* Bytes held by the mesh structures (cell and vertex pools, lists), the refiner's caches and
 * the fan stream. */
double hexlod_mesh_memory_bytes(const hexlod_terrain* terrain);
/* Live cells by kind (§4.2): out[0] full hexagons, out[1] interior semi-hexagons, out[2]
 * boundary semi-hexagons. Returns their total (= hexlod_mesh_cell_count), or -1. A pass over
 * the cell pool. */
int32_t hexlod_mesh_cell_kinds(const hexlod_terrain* terrain, int32_t* out);
/* Checks every invariant of the mesh; returns 0, or -1 with the violation in hexlod_last_error. */
int32_t hexlod_mesh_check(const hexlod_terrain* terrain);

/* --- The fan stream (paper §7) ---------------------------------------------------------------
 * What the renderer uploads, kept in step with the mesh: hexlod_lod_update changes the mesh,
 * hexlod_stream_update applies those changes to the arrays, rewriting only what changed.
 *
 * Vertices: the mesh's own vertex pool (vertex data exists once), 36 bytes a slot:
 *   bytes  0..11  position, 3 float32, metres (y unscaled: the shader multiplies heights by the
 *                 vertical exaggeration)
 *   bytes 12..19  normal, 4 snorm16 (x, y, z, 0), averaged from the adjacent triangles
 *   bytes 20..31  morph start, 3 float32, metres: the midpoint of the vertex's parent edge
 *   bytes 32..35  morph key, float32: 0 at rest; f+1 blending in since frame f; -(f+1)
 *                 blending out since frame f. With n = hexlod_lod_morph_frames and F the
 *                 current frame, the drawn position is mix(morph start, position, w), with
 *                 t = clamp((F - f) / n, 0, 1) and w = t blending in, 1 - t blending out,
 *                 1 at rest or when n = 0.
 * Free slots hold stale data and are never indexed.
 * Indices: a fixed slot per cell record: HEXLOD_LAYOUT_FANS, 9 indices (a triangle fan then
 * 0xFFFFFFFF; full hexagon: centre, six corners, first corner; boundary semi-hexagon: centre,
 * four corners; interior semi-hexagon: four corners from the fixed-rule corner; the rest of the
 * slot and free records: 0xFFFFFFFF), drawn as TRIANGLE_FAN with primitive restart; or
 * HEXLOD_LAYOUT_TRIANGLES, 18 indices (the same triangles as a list, padded with 0xFFFFFFFF).
 * The arrays stay valid until the next hexlod_stream_update, layout change or mesh reset. */
#define HEXLOD_LAYOUT_FANS 0
#define HEXLOD_LAYOUT_TRIANGLES 1

/* Applies the mesh's changes to the arrays; returns the version (it moves whenever anything
 * was written), or -1. Allocates only when the pools grew. */
int32_t hexlod_stream_update(hexlod_terrain* terrain);
/* Chooses the index layout (everything is rewritten). Returns 0 or -1. */
int32_t hexlod_stream_set_layout(hexlod_terrain* terrain, int32_t layout);
/* Whether the stream keeps the vertex normals (on: 1, the default; off: 0). Off, the normals in
 * the vertex pool are stale and the stream keeps no normal sums (24 bytes a vertex); turned
 * on, every normal is rebuilt exactly and the vertices are marked written. Returns 0 or -1. */
int32_t hexlod_stream_set_normals(hexlod_terrain* terrain, int32_t on);
int32_t hexlod_stream_version(const hexlod_terrain* terrain);
/* The vertex pool (see above) and its slot count; the index array and its length. */
const void* hexlod_stream_vertices(const hexlod_terrain* terrain);
int32_t hexlod_stream_vertex_count(const hexlod_terrain* terrain);
const uint32_t* hexlod_stream_indices(const hexlod_terrain* terrain);
int32_t hexlod_stream_index_count(const hexlod_terrain* terrain);
/* What changed since the last hexlod_stream_acknowledge, as (first, count) pairs of int32:
 * vertex slots and indices. The pointer is valid until the next call. The count is the number
 * of pairs. */
const int32_t* hexlod_stream_dirty_vertices(hexlod_terrain* terrain, int32_t* pair_count);
const int32_t* hexlod_stream_dirty_indices(hexlod_terrain* terrain, int32_t* pair_count);
/* The renderer has uploaded every dirty range: forget them. Returns 0. */
int32_t hexlod_stream_acknowledge(hexlod_terrain* terrain);

/* Height in metres (unscaled: times the vertical scale for the drawn world) of the surface as
 * drawn now at ground position (x_m, z_m): the triangles of the stream's index array, each
 * vertex where its geomorph blend puts it at the current frame (hexlod_lod_frame), the
 * highest where triangles meet. Call after hexlod_stream_update. Returns NaN where no drawn
 * triangle covers the point (outside the domain), or with no mesh. Scans every cell: about a
 * millisecond for 100k triangles. */
double hexlod_stream_drawn_height_at(const hexlod_terrain* terrain, double x_m, double z_m);

/* The level-ordered view for diagnostics (colour by level, hexagon outlines): every cell's fan
 * closed by 0xFFFFFFFF, grouped by level, and with outline non-zero every cell edge once as a
 * line pair. Written on each call (not incrementally). Returns the index count or -1. */
int32_t hexlod_stream_build_level_view(hexlod_terrain* terrain, int32_t outline);
const uint32_t* hexlod_stream_level_indices(const hexlod_terrain* terrain);
/* First index of each level 0..max_level in the level view, then its length: max_level + 2. */
const int32_t* hexlod_stream_level_offsets(const hexlod_terrain* terrain);
const uint32_t* hexlod_stream_outline(const hexlod_terrain* terrain);
int32_t hexlod_stream_outline_count(const hexlod_terrain* terrain);

/* --- View-dependent refinement (paper §5, §6) ------------------------------------------------
 * The refiner adapts the hexagon mesh so that, once converged, every sample inside the view
 * frustum deviates from the drawn surface by at most tau pixels on screen (or, in max-error
 * mode, every sample by at most max_error metres). Settings keep their values until changed. */

/* The camera: eye and target in metres (world frame: x east, y up, z south; heights already
 * times the vertical scale), an up vector, tan(vertical field of view / 2) (the caller computes
 * the tangent, so no transcendental function enters a split decision), width / height of the
 * viewport, its height in device pixels, and the near and far plane distances in metres.
 * Returns 0, or -1 for a degenerate camera. */
int32_t hexlod_lod_set_camera(hexlod_terrain* terrain, double eye_x, double eye_y, double eye_z,
                              double target_x, double target_y, double target_z, double up_x,
                              double up_y, double up_z, double tan_half_fov_y, double aspect,
                              double viewport_height_px, double near_m, double far_m);

/* Screen-space error tolerance tau in device pixels (> 0): switches to view-dependent mode. */
int32_t hexlod_lod_set_tolerance(hexlod_terrain* terrain, double tau_px);

/* Maximum vertical error in metres (> 0): switches to view-independent mode (every sample of
 * the field within max_error_m of the mesh, camera ignored). */
int32_t hexlod_lod_set_max_error(hexlod_terrain* terrain, double max_error_m);

/* Heights are drawn times vertical_scale (> 0). Changing it re-evaluates every cell. */
int32_t hexlod_lod_set_vertical_scale(hexlod_terrain* terrain, double vertical_scale);

/* Per-update budget: at most budget_ms milliseconds (<= 0: no time limit) and at most
 * max_operations splits and merges (<= 0: no limit). Every update makes at least one step of
 * progress. Returns 0. */
int32_t hexlod_lod_set_budget(hexlod_terrain* terrain, double budget_ms, int32_t max_operations);

/* Optional cap on drawn triangles (<= 0: none): no split starts while the mesh has more. With
 * auto_tau non-zero, tau is raised while the cap or the time budget is exceeded and lowered
 * back towards the set tolerance when there is room (paper §6, last sentence). */
int32_t hexlod_lod_set_limits(hexlod_terrain* terrain, int32_t max_triangles, int32_t auto_tau);

/* Frustum culling of cells (on by default; off refines outside the view as inside). */
int32_t hexlod_lod_set_culling(hexlod_terrain* terrain, int32_t enabled);

/* Back-face culling by the cells' cone of normals (on by default): a cell whose true surface
 * faces away from every point of its bounding sphere is left coarse; its samples cannot be
 * seen from an eye above the terrain. Exact embedding, cells of up to 4096 samples. */
int32_t hexlod_lod_set_backface_culling(hexlod_terrain* terrain, int32_t enabled);

/* Geomorphing (§7): a vertex the mesh creates blends from its parent edge's midpoint to its
 * place over `frames` frames, and a merge first blends the vertices it frees back and happens
 * when they have faded out. 0 (the default) turns it off. At most 1000. Returns 0 or -1. */
int32_t hexlod_lod_set_morph_frames(hexlod_terrain* terrain, int32_t frames);
/* The frame counter of the blends (one tick per hexlod_lod_update): the shader's F. */
double hexlod_lod_frame(const hexlod_terrain* terrain);
/* Merges waiting for their vertices to fade out. */
int32_t hexlod_lod_pending_merges(const hexlod_terrain* terrain);

/* Popping (for benchmarks): the largest screen-space jump of any vertex, in pixels, between
 * the frame now drawn and the one measured last, with the camera of the last
 * hexlod_lod_set_camera (see src/popping_meter.h); out[0] = max jump px, out[1] = jumps over
 * 0.5 px, out[2] = jumps measured; where the largest was: out[3], out[4] screen x, y in pixels
 * from the centre (y up), out[5] depth in metres, out[6] 0 a kept vertex, 1 a new one, 2 a
 * freed one. The first call only records the frame. Returns 0 or -1. */
int32_t hexlod_measure_popping(hexlod_terrain* terrain, double* out);

/* One refinement step (§6): re-test the cells whose margin the camera used up, refine the
 * failing ones (largest projected error first), then coarsen in descending level order,
 * until converged or out of budget; resumes where the last update stopped. The mesh is
 * consistent after every operation. Returns the number of operations done (splits, joins,
 * merges and breaks that the refiner asked for; forced splits count too), or -1. */
int32_t hexlod_lod_update(hexlod_terrain* terrain);

/* 1 when the last update tested every cell that was due, every failing test was resolved,
 * nothing is left to merge and no merge is waiting for a fade-out (converged). */
int32_t hexlod_lod_converged(const hexlod_terrain* terrain);

/* Figures of the last update: splits, merges, milliseconds spent, and the current tau (which
 * auto tau may have raised). */
int32_t hexlod_lod_last_splits(const hexlod_terrain* terrain);
int32_t hexlod_lod_last_merges(const hexlod_terrain* terrain);
double hexlod_lod_last_update_ms(const hexlod_terrain* terrain);
double hexlod_lod_current_tau(const hexlod_terrain* terrain);

/* The achieved screen error in pixels for the camera of the last hexlod_lod_set_camera: the
 * largest bound on the projected error (the refiner's criterion, §5) over the live cells in
 * view whose bound the refiner has computed (not back-facing, inside the frustum when culling
 * is on). At most tau once converged. -1 in max-error mode or with no mesh. A pass over the
 * cells. */
double hexlod_lod_achieved_error_px(const hexlod_terrain* terrain);

/* The mesh hash (cells, levels, lattice points and positions) as two 32-bit halves. */
uint32_t hexlod_mesh_hash_low(const hexlod_terrain* terrain);
uint32_t hexlod_mesh_hash_high(const hexlod_terrain* terrain);

/* Measures the current mesh against the samples (the error evaluator): writes max, p99 and
 * mean error in metres and the uncovered sample count to out[0..3]. against_stored = 1
 * compares with the field the core stores (for the shifted embedding, odd rows interpolated
 * at their shifted positions), 0 with the original samples at their true positions.
 * Returns 0 or -1. Costs a pass over every sample. */
int32_t hexlod_mesh_measure_error(const hexlod_terrain* terrain, int32_t against_stored, double* out);

#ifdef __cplusplus
}
#endif

#endif /* HEXLOD_H */
