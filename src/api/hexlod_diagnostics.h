/* hexlod_diagnostics.h: measurements of the core for tests, benchmarks and the command line
 * (paper §4 invariants, §5 error, §7 popping). Not part of the product: only the diagnostics
 * builds export these (native, build/wasm-diag for Node, build/wasm-tests); the page's
 * build/wasm does not. The conventions of hexlod.h hold: failures return HEXLOD_ERROR and set
 * hexlod_last_error(). */
#ifndef HEXLOD_DIAGNOSTICS_H
#define HEXLOD_DIAGNOSTICS_H

#include "hexlod.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Checks every invariant of the mesh (§4: neighbour symmetry, no hanging nodes, balance rule,
 * counters, free lists). 0, or HEXLOD_ERROR with the violation in hexlod_last_error(). */
int32_t hexlod_diag_check_mesh(const hexlod_terrain* terrain);

/* Checks that the stream draws a watertight surface (src/diagnostics/watertightness.h): the
 * triangles the GPU assembles from the index array (its layout, primitive restart) use live
 * vertex slots at finite positions, all counter-clockwise seen from above; every directed edge
 * is used once, so every interior edge by exactly two triangles; the edges used once form one
 * loop, and the Euler characteristic is 1 (one disc: no T-junction, crack or hole). Reads the
 * stream as the last frame's stream step left it. out (7 doubles, may be NULL): triangles,
 * vertices used, edges, boundary edges, boundary loops, Euler characteristic, indices read.
 * 0, or HEXLOD_ERROR with the first defect (and where) in hexlod_last_error(). */
int32_t hexlod_diag_check_stream(const hexlod_terrain* terrain, double* out);

/* The module's own allocator, all terrains together (for the soak benchmark's leak check):
 * out[0] bytes allocated and not freed, out[1] bytes the allocator holds from the system
 * (under WebAssembly, at most the memory size, which never shrinks). 0, or HEXLOD_ERROR where
 * the C library does not say (neither Emscripten's nor glibc's allocator). */
int32_t hexlod_diag_heap(double* out);

/* Splits every whole cell of the coarsest levels, `rounds` times: the uniform split (Fig. 4),
 * equal to that many 1-to-4 splits of the base triangulation. Returns the splits, or HEXLOD_ERROR. */
int32_t hexlod_diag_refine_uniform(hexlod_terrain* terrain, int32_t rounds);

/* Measures the mesh against the samples (a pass over every sample): out[0..3] = max, p99 and
 * mean error in metres, uncovered samples. against_stored non-zero compares with the field the
 * core stores (for the shifted embedding, odd rows interpolated at their shifted positions),
 * 0 with the original samples at their true positions. 0 or HEXLOD_ERROR. */
int32_t hexlod_diag_measure_error(const hexlod_terrain* terrain, int32_t against_stored, double* out);

/* Popping (§7): the largest screen-space jump of any vertex, in pixels, between the frame now
 * drawn and the one measured last, with the current camera (src/diagnostics/popping_meter.h):
 * out[0] max jump px, out[1] jumps over 0.5 px, out[2] jumps measured; where the largest was:
 * out[3], out[4] screen x, y in pixels from the centre (y up), out[5] depth in metres, out[6]
 * 0 a kept vertex, 1 a new one, 2 a freed one. The first call after a mesh reset only records
 * the frame. 0 or HEXLOD_ERROR. */
int32_t hexlod_diag_measure_popping(hexlod_terrain* terrain, double* out);

/* Fills *out with the settings in force, every zero given resolved to the default it stands for
 * (tau_px 1 where 0 was set; max_error_m stays 0 in tau mode): the core's defaults, for tests
 * that compare a caller's defaults with them. 0 or HEXLOD_ERROR. */
int32_t hexlod_diag_settings(const hexlod_terrain* terrain, hexlod_settings* out);

#ifdef __cplusplus
}
#endif

#endif /* HEXLOD_DIAGNOSTICS_H */
