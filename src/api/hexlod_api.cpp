// The C ABI declared in hexlod.h: thin wrappers that check the handle, call the core and turn
// failures into hexlod_last_error() messages. No logic of its own lives here.
#include "api/hexlod.h"

#include <cmath>
#include <memory>
#include <vector>

#include "stream/fan_stream.h"
#include "stream/drawn_surface.h"
#include "stream/geomorph.h"
#include "field/heightfield.h"
#include "mesh/hex_mesh.h"
#include "mesh/hex_mesh_refine.h"
#include "mesh/mesh_census.h"
#include "diagnostics/error_evaluator.h"
#include "diagnostics/popping_meter.h"
#include "lod/refiner.h"
#include "terrain.h"

// The handle: the terrain and the diagnostics' state kept per terrain.
struct hexlod_terrain {
    std::unique_ptr<hexlod::Terrain> core;
    hexlod::PoppingMeter popping;
    uint32_t poppingEpoch = 0; // the mesh the popping meter's last frame belongs to
};

namespace {

thread_local const char* lastError = "";

// Records a failure and returns the value the caller should return.
template <typename T>
T fail(const char* message, T result) {
    lastError = message;
    return result;
}

constexpr const char* kNullHandle = "the terrain handle is NULL (create it with hexlod_terrain_create)";
constexpr const char* kNoMesh = "the terrain has no hexagon mesh yet (call hexlod_mesh_reset)";

} // namespace

#define HEXLOD_NEED_MESH(result)                      \
    if (!terrain) return fail(kNullHandle, result);   \
    if (!terrain->core->hasMesh()) return fail(kNoMesh, result)

extern "C" {

uint32_t hexlod_abi_version(void) { return HEXLOD_ABI_VERSION; }

const char* hexlod_last_error(void) { return lastError; }

hexlod_terrain* hexlod_terrain_create(int32_t width, int32_t height, int32_t sample_type) {
    const char* error = nullptr;
    auto core = hexlod::Terrain::create(width, height, hexlod::SampleType(sample_type), &error);
    if (!core) return fail(error, static_cast<hexlod_terrain*>(nullptr));
    hexlod_terrain* terrain = new (std::nothrow) hexlod_terrain();
    if (!terrain) return fail("out of memory for the terrain", terrain);
    terrain->core = std::move(core);
    return terrain;
}

void hexlod_terrain_destroy(hexlod_terrain* terrain) { delete terrain; }

void* hexlod_terrain_samples(hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, static_cast<void*>(nullptr));
    return terrain->core->field().samples();
}

double hexlod_terrain_sample_bytes(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1.0);
    return double(terrain->core->field().byteSize());
}

int32_t hexlod_terrain_set_scale(hexlod_terrain* terrain, double spacing_x_m, double spacing_y_m,
                                 double height_scale, double height_offset_m, int32_t has_nodata,
                                 double nodata_raw) {
    if (!terrain) return fail(kNullHandle, -1);
    hexlod::HeightfieldScale scale;
    scale.spacingX = spacing_x_m;
    scale.spacingY = spacing_y_m;
    scale.heightScale = height_scale;
    scale.heightOffset = height_offset_m;
    scale.hasNodata = has_nodata != 0;
    scale.nodataRaw = nodata_raw;
    if (const char* error = terrain->core->setScale(scale)) return fail(error, -1);
    return 0;
}

double hexlod_terrain_prepare(hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1.0);
    if (const char* error = terrain->core->field().prepare()) return fail(error, -1.0);
    return double(terrain->core->field().missingCount());
}

double hexlod_terrain_min_height(const hexlod_terrain* terrain) {
    return terrain ? terrain->core->field().minHeight() : fail(kNullHandle, 0.0);
}

double hexlod_terrain_max_height(const hexlod_terrain* terrain) {
    return terrain ? terrain->core->field().maxHeight() : fail(kNullHandle, 0.0);
}

double hexlod_terrain_height_at(const hexlod_terrain* terrain, double x_m, double z_m) {
    return terrain ? terrain->core->field().heightAtPosition(x_m, z_m) : fail(kNullHandle, 0.0);
}

int32_t hexlod_mesh_reset(hexlod_terrain* terrain, int32_t embedding) {
    if (!terrain) return fail(kNullHandle, -1);
    if (embedding != HEXLOD_EMBEDDING_SHIFTED && embedding != HEXLOD_EMBEDDING_EXACT)
        return fail("unknown embedding (expected 0 = shifted, 1 = exact)", -1);
    if (const char* error = terrain->core->resetMesh(hexlod::Embedding(embedding))) return fail(error, -1);
    return 0;
}

int32_t hexlod_mesh_refine_uniform(hexlod_terrain* terrain, int32_t rounds) {
    HEXLOD_NEED_MESH(-1);
    return int32_t(terrain->core->refineUniform(rounds));
}

int32_t hexlod_mesh_max_level(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1);
    return terrain->core->hasMesh() ? terrain->core->mesh().maxLevel() : fail(kNoMesh, -1);
}

int32_t hexlod_mesh_triangle_count(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1);
    return terrain->core->hasMesh() ? int32_t(terrain->core->mesh().triangleCount()) : fail(kNoMesh, -1);
}

int32_t hexlod_mesh_cell_count(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1);
    return terrain->core->hasMesh() ? terrain->core->mesh().liveCells() : fail(kNoMesh, -1);
}

int32_t hexlod_mesh_vertex_count(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1);
    return terrain->core->hasMesh() ? terrain->core->mesh().liveVertices() : fail(kNoMesh, -1);
}

double hexlod_mesh_memory_bytes(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1.0);
    if (!terrain->core->hasMesh()) return fail(kNoMesh, -1.0);
    return double(terrain->core->memoryBytes());
}

int32_t hexlod_mesh_check(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1);
    if (!terrain->core->hasMesh()) return fail(kNoMesh, -1);
    if (const char* problem = terrain->core->mesh().checkInvariants()) return fail(problem, -1);
    return 0;
}

int32_t hexlod_stream_update(hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    terrain->core->syncStream();
    return int32_t(terrain->core->stream().version() & 0x7FFFFFFF);
}

int32_t hexlod_stream_set_layout(hexlod_terrain* terrain, int32_t layout) {
    HEXLOD_NEED_MESH(-1);
    if (layout != HEXLOD_LAYOUT_FANS && layout != HEXLOD_LAYOUT_TRIANGLES)
        return fail("unknown index layout (expected 0 = fans, 1 = triangles)", -1);
    terrain->core->stream().setLayout(hexlod::IndexLayout(layout));
    return 0;
}

int32_t hexlod_stream_set_normals(hexlod_terrain* terrain, int32_t on) {
    HEXLOD_NEED_MESH(-1);
    if (on != 0 && on != 1) return fail("stream normals are on (1) or off (0)", -1);
    terrain->core->stream().setNormals(on == 1);
    return 0;
}

int32_t hexlod_stream_version(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return int32_t(terrain->core->stream().version() & 0x7FFFFFFF);
}

const void* hexlod_stream_vertices(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(static_cast<const void*>(nullptr));
    return terrain->core->mesh().vertexData();
}

int32_t hexlod_stream_vertex_count(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->mesh().vertexCapacity();
}

const uint32_t* hexlod_stream_indices(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(static_cast<const uint32_t*>(nullptr));
    return terrain->core->stream().indices().data();
}

int32_t hexlod_stream_index_count(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->stream().indexCount();
}

namespace {
const int32_t* rangePairs(const std::vector<hexlod::ElementRange>& ranges, int32_t* pair_count) {
    static_assert(sizeof(hexlod::ElementRange) == 2 * sizeof(int32_t), "ranges are read as int32 pairs");
    if (pair_count) *pair_count = int32_t(ranges.size());
    return ranges.empty() ? nullptr : &ranges[0].first;
}
} // namespace

const int32_t* hexlod_stream_dirty_vertices(hexlod_terrain* terrain, int32_t* pair_count) {
    HEXLOD_NEED_MESH(static_cast<const int32_t*>(nullptr));
    return rangePairs(terrain->core->stream().dirtyVertices(), pair_count);
}

const int32_t* hexlod_stream_dirty_indices(hexlod_terrain* terrain, int32_t* pair_count) {
    HEXLOD_NEED_MESH(static_cast<const int32_t*>(nullptr));
    return rangePairs(terrain->core->stream().dirtyIndices(), pair_count);
}

int32_t hexlod_stream_acknowledge(hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    terrain->core->stream().acknowledge();
    return 0;
}

int32_t hexlod_stream_build_level_view(hexlod_terrain* terrain, int32_t outline) {
    HEXLOD_NEED_MESH(-1);
    terrain->core->stream().buildLevelView(terrain->core->mesh(), outline != 0);
    return int32_t(terrain->core->stream().levelIndices().size());
}

const uint32_t* hexlod_stream_level_indices(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(static_cast<const uint32_t*>(nullptr));
    return terrain->core->stream().levelIndices().data();
}

const int32_t* hexlod_stream_level_offsets(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(static_cast<const int32_t*>(nullptr));
    return terrain->core->stream().levelOffsets().data();
}

const uint32_t* hexlod_stream_outline(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(static_cast<const uint32_t*>(nullptr));
    return terrain->core->stream().outline().data();
}

int32_t hexlod_stream_outline_count(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return int32_t(terrain->core->stream().outline().size());
}

int32_t hexlod_lod_set_morph_frames(hexlod_terrain* terrain, int32_t frames) {
    HEXLOD_NEED_MESH(-1);
    if (frames < 0 || frames > hexlod::Geomorph::kMaxFrames) return fail("morph frames must be 0 (off) to 1000", -1);
    terrain->core->morph().setFrames(frames);
    return 0;
}

double hexlod_lod_frame(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1.0);
    return double(terrain->core->morph().frame());
}

int32_t hexlod_lod_pending_merges(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->refiner().pendingMerges();
}

int32_t hexlod_measure_popping(hexlod_terrain* terrain, double* out) {
    HEXLOD_NEED_MESH(-1);
    if (!out) return fail("out must point to 7 doubles", -1);
    if (terrain->poppingEpoch != terrain->core->meshEpoch()) terrain->popping.reset(); // a new mesh: start again
    terrain->poppingEpoch = terrain->core->meshEpoch();
    const hexlod::PoppingStats stats = terrain->popping.measure(terrain->core->mesh(), terrain->core->morph(), terrain->core->refiner().view(),
                                                                terrain->core->refiner().settings().verticalScale);
    out[0] = stats.maxJumpPx;
    out[1] = double(stats.jumpsOverHalfPx);
    out[2] = double(stats.measured);
    out[3] = stats.atX;
    out[4] = stats.atY;
    out[5] = stats.atDepth;
    out[6] = double(stats.kind);
    return 0;
}

int32_t hexlod_lod_set_camera(hexlod_terrain* terrain, double eye_x, double eye_y, double eye_z,
                              double target_x, double target_y, double target_z, double up_x,
                              double up_y, double up_z, double tan_half_fov_y, double aspect,
                              double viewport_height_px, double near_m, double far_m) {
    HEXLOD_NEED_MESH(-1);
    hexlod::View view;
    if (!hexlod::makeView({eye_x, eye_y, eye_z}, {target_x, target_y, target_z}, {up_x, up_y, up_z}, tan_half_fov_y,
                          aspect, viewport_height_px, near_m, far_m, view))
        return fail("degenerate camera: eye on the target, up along the view, or a non-positive size or plane", -1);
    terrain->core->refiner().setView(view); // marks the cycle changed only when the camera moved
    return 0;
}

int32_t hexlod_lod_set_tolerance(hexlod_terrain* terrain, double tau_px) {
    HEXLOD_NEED_MESH(-1);
    if (!(tau_px > 0.0) || !std::isfinite(tau_px)) return fail("tau must be a positive number of pixels", -1);
    hexlod::RefinerSettings& s = terrain->core->refiner().settings();
    s.viewIndependent = false;
    s.tau = tau_px;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_set_max_error(hexlod_terrain* terrain, double max_error_m) {
    HEXLOD_NEED_MESH(-1);
    if (!(max_error_m > 0.0) || !std::isfinite(max_error_m)) return fail("the maximum error must be a positive number of metres", -1);
    hexlod::RefinerSettings& s = terrain->core->refiner().settings();
    s.viewIndependent = true;
    s.maxError = max_error_m;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_set_vertical_scale(hexlod_terrain* terrain, double vertical_scale) {
    HEXLOD_NEED_MESH(-1);
    if (!(vertical_scale > 0.0) || !std::isfinite(vertical_scale)) return fail("the vertical scale must be a positive number", -1);
    terrain->core->refiner().settings().verticalScale = vertical_scale;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_set_budget(hexlod_terrain* terrain, double budget_ms, int32_t max_operations) {
    HEXLOD_NEED_MESH(-1);
    hexlod::RefinerSettings& s = terrain->core->refiner().settings();
    s.budgetMs = std::isfinite(budget_ms) ? budget_ms : 0.0;
    s.maxOperations = max_operations;
    return 0;
}

int32_t hexlod_lod_set_limits(hexlod_terrain* terrain, int32_t max_triangles, int32_t auto_tau) {
    HEXLOD_NEED_MESH(-1);
    hexlod::RefinerSettings& s = terrain->core->refiner().settings();
    s.maxTriangles = max_triangles;
    s.autoTau = auto_tau != 0;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_set_culling(hexlod_terrain* terrain, int32_t enabled) {
    HEXLOD_NEED_MESH(-1);
    terrain->core->refiner().settings().culling = enabled != 0;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_set_backface_culling(hexlod_terrain* terrain, int32_t enabled) {
    HEXLOD_NEED_MESH(-1);
    terrain->core->refiner().settings().backfaceCulling = enabled != 0;
    terrain->core->refiner().markChanged();
    return 0;
}

int32_t hexlod_lod_update(hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->refiner().update().operations;
}

int32_t hexlod_lod_converged(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    // The refiner's convergence does not wait for fades (issue 12); the page must keep
    // updating until the faded merges are done, so this also asks for none pending.
    return terrain->core->converged() ? 1 : 0;
}

int32_t hexlod_lod_last_splits(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->refiner().lastUpdate().splits;
}

int32_t hexlod_lod_last_merges(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1);
    return terrain->core->refiner().lastUpdate().merges;
}

double hexlod_lod_last_update_ms(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1.0);
    return terrain->core->refiner().lastUpdate().milliseconds;
}

double hexlod_lod_current_tau(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1.0);
    return terrain->core->refiner().currentTau();
}

double hexlod_lod_achieved_error_px(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(-1.0);
    return terrain->core->refiner().achievedErrorPixels();
}

int32_t hexlod_mesh_cell_kinds(const hexlod_terrain* terrain, int32_t* out) {
    HEXLOD_NEED_MESH(-1);
    if (!out) return fail("hexlod_mesh_cell_kinds needs an array of 3 int32 to write to", -1);
    const auto counts = hexlod::countCellKinds(terrain->core->mesh());
    for (size_t k = 0; k < 3; ++k) out[k] = counts[k];
    return counts[0] + counts[1] + counts[2];
}

double hexlod_stream_drawn_height_at(const hexlod_terrain* terrain, double x_m, double z_m) {
    if (!terrain || !terrain->core->hasMesh()) return std::nan("");
    float height = 0.0f;
    if (!terrain->core->drawnHeightAt(x_m, z_m, height)) return std::nan("");
    return double(height);
}

uint32_t hexlod_mesh_hash_low(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(0u);
    return uint32_t(terrain->core->mesh().hash());
}

uint32_t hexlod_mesh_hash_high(const hexlod_terrain* terrain) {
    HEXLOD_NEED_MESH(0u);
    return uint32_t(terrain->core->mesh().hash() >> 32);
}

int32_t hexlod_mesh_measure_error(const hexlod_terrain* terrain, int32_t against_stored, double* out) {
    HEXLOD_NEED_MESH(-1);
    if (!out) return fail("out must point to 4 doubles", -1);
    std::vector<uint32_t> triangles;
    terrain->core->mesh().appendTriangles(triangles);
    hexlod::ErrorOptions options;
    options.shiftedOddRows = against_stored != 0 && terrain->core->mesh().embedding() == hexlod::Embedding::Shifted;
    const hexlod::ErrorStats stats = hexlod::evaluateMeshError(terrain->core->field(), terrain->core->mesh().positionData(),
                                                               size_t(terrain->core->mesh().vertexCapacity()), hexlod::kStreamVertexWords, triangles.data(),
                                                               triangles.size(), options);
    if (stats.error) return fail(stats.error, -1);
    out[0] = stats.maxError;
    out[1] = stats.p99Error;
    out[2] = stats.meanError;
    out[3] = double(stats.uncovered);
    return 0;
}

} // extern "C"
