// The product C ABI declared in hexlod.h: thin wrappers that check their arguments, drive the
// terrain facade (terrain.h) and turn failures into hexlod_last_error() messages. No logic of
// the paper lives here.
#include "api/hexlod.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <new>
#include <vector>

#include "api/hexlod_inputs.h"
#include "api/terrain_handle.h"
#include "mesh/mesh_census.h"

// JS reads the structs through views at the offsets hexlod_struct_layout() reports (web/core/core.js);
// these pin the wasm32 sizes that the header documents.
#if UINTPTR_MAX == 0xFFFFFFFFu
static_assert(sizeof(hexlod_scale) == 48 && offsetof(hexlod_scale, has_nodata) == 40, "hexlod_scale layout");
static_assert(sizeof(hexlod_field_info) == 32, "hexlod_field_info layout");
static_assert(sizeof(hexlod_settings) == 64 && offsetof(hexlod_settings, max_operations) == 32, "hexlod_settings layout");
static_assert(sizeof(hexlod_camera) == 112 && offsetof(hexlod_camera, near_m) == 96, "hexlod_camera layout");
static_assert(offsetof(hexlod_frame, version) == 56 && offsetof(hexlod_frame, vertex_count) == 56 + 4 * 15 &&
                  offsetof(hexlod_frame, vertices_ptr) == 172 && sizeof(hexlod_frame) == 192,
              "hexlod_frame layout");
static_assert(offsetof(hexlod_level_view, index_count) == 12 && sizeof(hexlod_level_view) == 24, "hexlod_level_view layout");
#endif

namespace {
thread_local const char* lastError = "";
} // namespace

void hexlod::api::setError(const char* message) { lastError = message; }

using hexlod::api::fail;
using hexlod::api::kNullHandle;
using hexlod::api::needMesh;

namespace {

// The ranges as (first, count) int32 pairs.
const int32_t* rangePairs(const std::vector<hexlod::ElementRange>& ranges) {
    static_assert(sizeof(hexlod::ElementRange) == 2 * sizeof(int32_t), "ranges are read as int32 pairs");
    return ranges.empty() ? nullptr : &ranges[0].first;
}

void fillFrame(hexlod_terrain* terrain, int32_t steps, hexlod_frame* out) {
    hexlod::Terrain& core = *terrain->core;
    const hexlod::HexMesh& mesh = core.mesh();
    const hexlod::Refiner& refiner = core.refiner();
    const hexlod::UpdateStats& last = refiner.lastUpdate();
    const hexlod::FanStream& stream = core.stream();
    out->update_ms = last.milliseconds;
    out->tau_px = refiner.currentTau();
    out->frame = double(core.morph().frame());
    out->memory_bytes = double(core.memoryBytes());
    out->triangles = double(mesh.triangleCount());
    out->version = int32_t(stream.version() & 0x7FFFFFFF);
    out->converged = core.converged() ? 1 : 0;
    out->refined = last.converged ? 1 : 0;
    out->operations = last.operations;
    out->splits = last.splits;
    out->merges = last.merges;
    out->cells_tested = last.cellsTested;
    out->pending_merges = refiner.pendingMerges();
    out->cells = mesh.liveCells();
    out->vertices = mesh.liveVertices();
    out->max_level = mesh.maxLevel();
    if (const hexlod::SampleTiles* tiles = core.field().tiles()) {
        out->tile_bytes = core.residency().heldBytes(*tiles);
        out->tiles_evicted = int32_t(std::min<int64_t>(core.residency().evictions(), INT32_MAX));
    }
    if (steps & HEXLOD_FRAME_CENSUS) {
        const auto kinds = hexlod::countCellKinds(mesh);
        out->full_hexagons = kinds[0];
        out->semi_hexagons = kinds[1];
        out->boundary_semi_hexagons = kinds[2];
        out->achieved_error_px = refiner.achievedErrorPixels();
    }
    if (steps & HEXLOD_FRAME_HASH) {
        const uint64_t hash = mesh.hash();
        out->hash_low = uint32_t(hash);
        out->hash_high = uint32_t(hash >> 32);
    }
    out->vertex_count = mesh.vertexCapacity();
    out->index_count = stream.indexCount();
    out->dirty_vertex_pairs = int32_t(core.dirtyVertexRanges().size()); // collecting the dirty ranges sorts them
    out->dirty_index_pairs = int32_t(core.dirtyIndexRanges().size());
    out->vertices_ptr = mesh.vertexData();
    out->indices_ptr = stream.indices().data();
    out->dirty_vertices_ptr = rangePairs(core.dirtyVertexRanges());
    out->dirty_indices_ptr = rangePairs(core.dirtyIndexRanges());
    out->normals_ptr = stream.normalData();
}

} // namespace

extern "C" {

uint32_t hexlod_abi_version(void) { return HEXLOD_ABI_VERSION; }

const char* hexlod_last_error(void) { return lastError; }

hexlod_terrain* hexlod_terrain_create(int32_t width, int32_t height, int32_t sample_type) {
    const char* error = nullptr;
    auto core = hexlod::Terrain::create(width, height, hexlod::SampleType(sample_type), &error);
    if (!core) return fail(error), nullptr;
    hexlod_terrain* terrain = new (std::nothrow) hexlod_terrain();
    if (!terrain) return fail("out of memory for the terrain"), nullptr;
    terrain->core = std::move(core);
    return terrain;
}

hexlod_terrain* hexlod_terrain_create_tiled(int32_t width, int32_t height, int32_t sample_type, int32_t level_count,
                                            const int32_t* dims) {
    const char* error = nullptr;
    auto core = hexlod::Terrain::createTiled(width, height, hexlod::SampleType(sample_type), level_count, dims, &error);
    if (!core) return fail(error), nullptr;
    hexlod_terrain* terrain = new (std::nothrow) hexlod_terrain();
    if (!terrain) return fail("out of memory for the terrain"), nullptr;
    terrain->core = std::move(core);
    return terrain;
}

void* hexlod_terrain_tile_buffer(hexlod_terrain* terrain, int32_t level, int32_t tx, int32_t ty) {
    if (!terrain) return fail(kNullHandle), nullptr;
    if (!terrain->core->field().tiles()) return fail("the terrain holds its samples whole: it has no tiles"), nullptr;
    void* buffer = terrain->core->tileBuffer(level, tx, ty);
    if (!buffer) return fail("no such tile (level or tile outside the terrain's), or out of memory for it"), nullptr;
    return buffer;
}

int32_t hexlod_terrain_commit_tile(hexlod_terrain* terrain, int32_t level, int32_t tx, int32_t ty) {
    if (!terrain) return fail(kNullHandle);
    if (!terrain->core->commitTile(level, tx, ty)) return fail("the tile has no buffer to commit (ask hexlod_terrain_tile_buffer first)");
    return 0;
}

int32_t hexlod_terrain_set_tile_cap(hexlod_terrain* terrain, double cap_bytes) {
    if (!terrain) return fail(kNullHandle);
    if (!terrain->core->field().tiles()) return fail("the terrain holds its samples whole: it has no tiles");
    if (!terrain->core->setTileCap(cap_bytes)) return fail("the tile cap must be a number of bytes >= 0");
    return 0;
}

int32_t hexlod_terrain_set_void_fill(hexlod_terrain* terrain, int32_t fill) {
    if (!terrain) return fail(kNullHandle);
    if (fill != HEXLOD_VOIDS_SURFACE && fill != HEXLOD_VOIDS_LOWEST) return fail("the void fill must be HEXLOD_VOIDS_SURFACE or HEXLOD_VOIDS_LOWEST");
    if (!terrain->core->setVoidsAsPits(fill == HEXLOD_VOIDS_LOWEST)) return fail("the terrain holds its samples whole: its caller fills its voids");
    return 0;
}

int32_t hexlod_terrain_declare_height_range(hexlod_terrain* terrain, double low_m, double high_m) {
    if (!terrain) return fail(kNullHandle);
    if (const char* error = terrain->core->declareHeightRange(low_m, high_m)) return fail(error);
    return 0;
}

namespace {

int32_t handOut(hexlod_terrain* terrain, const std::vector<hexlod::TileWant>& found, const hexlod_tile_want** wants) {
    std::vector<hexlod_tile_want>& out = terrain->wants;
    out.resize(found.size());
    for (size_t k = 0; k < found.size(); ++k) out[k] = {found[k].level, found[k].tx, found[k].ty, 0, double(found[k].priority)};
    if (wants) *wants = out.data();
    return int32_t(out.size());
}

} // namespace


int32_t hexlod_terrain_tile_wants(hexlod_terrain* terrain, const hexlod_tile_want** wants) {
    if (const char* problem = needMesh(terrain)) return fail(problem);
    return handOut(terrain, terrain->core->tileWants(), wants);
}

void hexlod_terrain_destroy(hexlod_terrain* terrain) { delete terrain; }

void* hexlod_terrain_samples(hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle), nullptr;
    if (terrain->core->field().tiles()) return fail("a tiled terrain has no whole sample array (write its tiles: hexlod_terrain_tile_buffer)"), nullptr;
    return terrain->core->field().samples();
}

int32_t hexlod_terrain_set_scale(hexlod_terrain* terrain, const hexlod_scale* scale) {
    if (!terrain) return fail(kNullHandle);
    if (!scale) return fail("hexlod_terrain_set_scale needs a hexlod_scale");
    hexlod::HeightfieldScale s;
    s.spacingX = scale->spacing_x_m != 0.0 ? scale->spacing_x_m : 1.0;
    s.spacingY = scale->spacing_y_m != 0.0 ? scale->spacing_y_m : 1.0;
    s.heightScale = scale->height_scale != 0.0 ? scale->height_scale : 1.0;
    s.heightOffset = scale->height_offset_m;
    s.hasNodata = scale->has_nodata != 0;
    s.nodataRaw = scale->nodata_raw;
    if (const char* error = terrain->core->setScale(s)) return fail(error);
    return 0;
}

int32_t hexlod_terrain_prepare(hexlod_terrain* terrain, hexlod_field_info* info) {
    if (!terrain) return fail(kNullHandle);
    const hexlod::Heightfield& field = terrain->core->field();
    if (const char* error = terrain->core->prepare()) return fail(error);
    if (info) {
        info->min_height_m = field.minHeight();
        info->max_height_m = field.maxHeight();
        info->missing = double(field.missingCount());
        info->sample_bytes = double(field.byteSize());
    }
    return 0;
}

int32_t hexlod_terrain_reset_mesh(hexlod_terrain* terrain, const hexlod_mesh_settings* settings) {
    if (!terrain) return fail(kNullHandle);
    const int32_t embedding = settings ? settings->embedding : HEXLOD_EMBEDDING_EXACT;
    if (embedding != HEXLOD_EMBEDDING_EXACT && embedding != HEXLOD_EMBEDDING_SHIFTED)
        return fail("unknown embedding (expected 0 = exact, 1 = shifted)");
    const hexlod::Embedding e = embedding == HEXLOD_EMBEDDING_SHIFTED ? hexlod::Embedding::Shifted : hexlod::Embedding::Exact;
    if (const char* error = terrain->core->resetMesh(e)) return fail(error);
    return 0;
}

int32_t hexlod_terrain_set_settings(hexlod_terrain* terrain, const hexlod_settings* settings) {
    if (!terrain) return fail(kNullHandle);
    const hexlod_settings defaults{};
    const hexlod_settings& in = settings ? *settings : defaults;
    if (const char* error = hexlod::api::checkSettings(in)) return fail(error); // the previous settings stay
    hexlod::TerrainSettings s; // zero means default: the defaults are the C++ structs' own
    s.lod.viewIndependent = in.max_error_m > 0.0;
    if (in.tau_px > 0.0) s.lod.tau = in.tau_px;
    if (in.max_error_m > 0.0) s.lod.maxError = in.max_error_m;
    if (in.vertical_scale > 0.0) s.lod.verticalScale = in.vertical_scale;
    s.lod.budgetMs = in.budget_ms;
    s.lod.maxOperations = in.max_operations;
    s.lod.maxTriangles = in.max_triangles;
    s.lod.autoTau = in.auto_tau != 0;
    s.lod.culling = in.no_frustum_culling == 0;
    s.lod.backfaceCulling = in.no_backface_culling == 0;
    s.morphFrames = in.morph_frames;
    s.layout = hexlod::IndexLayout(in.layout);
    s.normals = in.no_normals == 0;
    s.lod.earth = terrain->core->settings().lod.earth; // set apart, by hexlod_terrain_set_earth
    terrain->core->configure(s);
    return 0;
}

int32_t hexlod_terrain_set_earth(hexlod_terrain* terrain, int32_t kind, double origin_x_m, double origin_z_m, double radius_m,
                                 double latitude0_rad, double metres_per_radian_x, double metres_per_radian_z) {
    if (!terrain) return fail(kNullHandle);
    hexlod::EarthShape earth;
    if (const char* error = hexlod::api::checkEarth(kind, origin_x_m, origin_z_m, radius_m, latitude0_rad, metres_per_radian_x,
                                                    metres_per_radian_z, earth))
        return fail(error);
    hexlod::TerrainSettings s = terrain->core->settings();
    s.lod.earth = earth;
    terrain->core->configure(s);
    return 0;
}

int32_t hexlod_terrain_frame(hexlod_terrain* terrain, const hexlod_camera* camera, int32_t steps, hexlod_frame* out) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (!out) return fail("hexlod_terrain_frame needs a hexlod_frame to fill");
    constexpr int32_t kSteps = HEXLOD_FRAME_CAMERA | HEXLOD_FRAME_LOD | HEXLOD_FRAME_STREAM;
    constexpr int32_t kAll = kSteps | HEXLOD_FRAME_QUERY | HEXLOD_FRAME_HASH | HEXLOD_FRAME_CENSUS;
    if (steps & ~kAll) return fail("unknown frame steps (expected a sum of HEXLOD_FRAME_* bits, 0 to 63)");
    if (!(steps & (kSteps | HEXLOD_FRAME_QUERY))) steps |= kSteps;
    if (steps & HEXLOD_FRAME_QUERY) steps &= ~kSteps;
    hexlod::Terrain& core = *terrain->core;
    if ((steps & HEXLOD_FRAME_CAMERA) && camera) {
        // A refused camera fails the whole frame: the previous camera, mesh and stream stay.
        glm::dvec3 up;
        if (const char* error = hexlod::api::checkCamera(*camera, &up)) return fail(error);
        hexlod::View view;
        if (!hexlod::makeView({camera->eye[0], camera->eye[1], camera->eye[2]},
                              {camera->target[0], camera->target[1], camera->target[2]}, up, camera->tan_half_fov_y,
                              camera->aspect, camera->viewport_height_px, camera->near_m, camera->far_m, view))
            return fail("degenerate camera: eye on the target, up along the view, or a non-positive size or plane");
        core.setView(view); // the refiner re-tests only what the camera's movement may have changed
    }
    if (steps & HEXLOD_FRAME_LOD) core.updateLod();
    if (steps & HEXLOD_FRAME_STREAM) core.syncStream();
    fillFrame(terrain, steps, out);
    return 0;
}

int32_t hexlod_terrain_acknowledge(hexlod_terrain* terrain) {
    if (const char* error = needMesh(terrain)) return fail(error);
    terrain->core->acknowledgeStream();
    return 0;
}

int32_t hexlod_terrain_height_at(const hexlod_terrain* terrain, double x_m, double z_m, int32_t surface, double* height_m) {
    if (!terrain) return fail(kNullHandle);
    if (!height_m) return fail("hexlod_terrain_height_at needs a double to write to");
    if (surface != HEXLOD_SURFACE_FIELD && surface != HEXLOD_SURFACE_DRAWN) return fail("unknown surface (expected 0 = field, 1 = drawn)");
    if (surface == HEXLOD_SURFACE_DRAWN)
        if (const char* error = needMesh(terrain)) return fail(error);
    if (!std::isfinite(x_m) || !std::isfinite(z_m)) { // no surface lies there (and NaN must not reach an index)
        *height_m = std::nan("");
        return 0;
    }
    if (surface == HEXLOD_SURFACE_FIELD) {
        *height_m = terrain->core->field().heightAtPosition(x_m, z_m);
        return 1;
    }
    float height = 0.0f;
    if (!terrain->core->drawnHeightAt(x_m, z_m, height)) {
        *height_m = std::nan("");
        return 0;
    }
    *height_m = double(height);
    return 1;
}

int32_t hexlod_terrain_level_view(hexlod_terrain* terrain, int32_t outline, hexlod_level_view* out) {
    if (const char* error = needMesh(terrain)) return fail(error);
    if (!out) return fail("hexlod_terrain_level_view needs a hexlod_level_view to fill");
    terrain->core->buildLevelView(outline != 0);
    const hexlod::FanStream& stream = terrain->core->stream();
    out->indices = stream.levelIndices().data();
    out->level_offsets = stream.levelOffsets().data();
    out->outline = stream.outline().data();
    out->index_count = int32_t(stream.levelIndices().size());
    out->level_offset_count = int32_t(stream.levelOffsets().size());
    out->outline_count = int32_t(stream.outline().size());
    return out->index_count;
}

} // extern "C"
