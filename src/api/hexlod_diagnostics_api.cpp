// The diagnostics ABI declared in hexlod_diagnostics.h (paper §4 invariants, §5 error, §7
// popping): thin wrappers over the core and src/diagnostics/. Linked into the native library
// and the diagnostics WASM builds only.
#include "api/hexlod_diagnostics.h"

#include <malloc.h> // mallinfo: Emscripten's dlmalloc, glibc's mallinfo2

#include <algorithm>
#include <vector>

#include "api/terrain_handle.h"
#include "diagnostics/error_evaluator.h"
#include "diagnostics/watertightness.h"

using hexlod::api::fail;
using hexlod::api::kNullHandle;
using hexlod::api::needMesh;

extern "C" {

int32_t hexlod_diag_check_mesh(const hexlod_terrain* terrain) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (const char* problem = terrain->core->mesh().checkInvariants()) return fail(problem);
    return 0;
}

int32_t hexlod_diag_check_stream(const hexlod_terrain* terrain, double* out) {
    if (const char* error = needMesh(terrain)) return fail(error);
    const hexlod::HexMesh& mesh = terrain->core->mesh();
    const hexlod::FanStream& stream = terrain->core->stream();
    const std::vector<uint32_t>& indices = stream.indices();
    std::vector<uint32_t> triangles;
    hexlod::assembleTriangles(indices.data(), indices.size(),
                              stream.layout() == hexlod::IndexLayout::Fans ? hexlod::Primitive::TriangleFan : hexlod::Primitive::Triangles,
                              triangles);
    const hexlod::WatertightStats stats =
        hexlod::checkWatertight(triangles, mesh.positionData(), size_t(mesh.vertexCapacity()), hexlod::kStreamVertexWords,
                                [&mesh](uint32_t v) { return mesh.isVertexLive(int32_t(v)); });
    if (out) {
        const double figures[7] = {double(stats.triangles), double(stats.vertices), double(stats.edges), double(stats.boundaryEdges),
                                   double(stats.boundaryLoops), double(stats.euler), double(indices.size())};
        std::copy(figures, figures + 7, out);
    }
    if (stats.error) return fail(stats.error);
    return 0;
}

int32_t hexlod_diag_heap(double* out) {
    if (!out) return fail("out must point to 2 doubles");
#if defined(__EMSCRIPTEN__)
    const struct mallinfo info = mallinfo();
    out[0] = double(unsigned(info.uordblks));
    out[1] = double(unsigned(info.arena));
#elif defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 info = mallinfo2();
    out[0] = double(info.uordblks + info.hblkhd); // small chunks and mmapped ones
    out[1] = double(info.arena + info.hblkhd);
#else
    return fail("this C library does not report its heap");
#endif
    return 0;
}

int32_t hexlod_diag_settings(const hexlod_terrain* terrain, hexlod_settings* out) {
    if (!terrain) return fail(kNullHandle);
    if (!out) return fail("hexlod_diag_settings needs a hexlod_settings to fill");
    const hexlod::TerrainSettings s = terrain->core->settings();
    *out = hexlod_settings{};
    out->tau_px = s.lod.tau;
    out->max_error_m = s.lod.viewIndependent ? s.lod.maxError : 0.0;
    out->vertical_scale = s.lod.verticalScale;
    out->budget_ms = s.lod.budgetMs;
    out->max_operations = s.lod.maxOperations;
    out->max_triangles = s.lod.maxTriangles;
    out->auto_tau = s.lod.autoTau ? 1 : 0;
    out->no_frustum_culling = s.lod.culling ? 0 : 1;
    out->no_backface_culling = s.lod.backfaceCulling ? 0 : 1;
    out->morph_frames = s.morphFrames;
    out->layout = int32_t(s.layout);
    out->no_normals = s.normals ? 0 : 1;
    return 0;
}

int32_t hexlod_diag_refine_uniform(hexlod_terrain* terrain, int32_t rounds) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (rounds < 0) return fail("the rounds of uniform refinement must be 0 or more");
    return int32_t(terrain->core->refineUniform(rounds));
}

int32_t hexlod_diag_measure_error(const hexlod_terrain* terrain, int32_t against_stored, double* out) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (!out) return fail("out must point to 4 doubles");
    const hexlod::HexMesh& mesh = terrain->core->mesh();
    std::vector<uint32_t> triangles;
    mesh.appendTriangles(triangles);
    hexlod::ErrorOptions options;
    options.shiftedOddRows = against_stored != 0 && mesh.embedding() == hexlod::Embedding::Shifted;
    const hexlod::ErrorStats stats =
        hexlod::evaluateMeshError(terrain->core->field(), mesh.positionData(), size_t(mesh.vertexCapacity()),
                                  hexlod::kStreamVertexWords, triangles.data(), triangles.size(), options);
    if (stats.error) return fail(stats.error);
    out[0] = stats.maxError;
    out[1] = stats.p99Error;
    out[2] = stats.meanError;
    out[3] = double(stats.uncovered);
    return 0;
}

int32_t hexlod_diag_measure_popping(hexlod_terrain* terrain, double* out) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (!out) return fail("out must point to 7 doubles");
    hexlod::Terrain& core = *terrain->core;
    terrain->popping.follow(core.meshEpoch(), core.renumberings(), core.lastRenumbering());
    const hexlod::PoppingStats stats =
        terrain->popping.measure(core.mesh(), core.morph(), core.refiner().view(), core.refiner().settings().verticalScale);
    out[0] = stats.maxJumpPx;
    out[1] = double(stats.jumpsOverHalfPx);
    out[2] = double(stats.measured);
    out[3] = stats.atX;
    out[4] = stats.atY;
    out[5] = stats.atDepth;
    out[6] = double(stats.kind);
    return 0;
}

} // extern "C"
