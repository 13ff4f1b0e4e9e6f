// The C ABI declared in hexlod.h: thin wrappers that check the handle, call the core and turn
// failures into hexlod_last_error() messages. No logic of its own lives here.
#include "hexlod.h"

#include <memory>

#include "grid_mesh.h"
#include "heightfield.h"

struct hexlod_terrain {
    std::unique_ptr<hexlod::Heightfield> field;
    hexlod::GridMesh grid;
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

} // namespace

extern "C" {

uint32_t hexlod_abi_version(void) { return HEXLOD_ABI_VERSION; }

const char* hexlod_last_error(void) { return lastError; }

hexlod_terrain* hexlod_terrain_create(int32_t width, int32_t height, int32_t sample_type) {
    const char* error = nullptr;
    auto field = hexlod::Heightfield::create(width, height, hexlod::SampleType(sample_type), &error);
    if (!field) return fail(error, static_cast<hexlod_terrain*>(nullptr));
    hexlod_terrain* terrain = new (std::nothrow) hexlod_terrain();
    if (!terrain) return fail("out of memory for the terrain", terrain);
    terrain->field = std::move(field);
    return terrain;
}

void hexlod_terrain_destroy(hexlod_terrain* terrain) { delete terrain; }

void* hexlod_terrain_samples(hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, static_cast<void*>(nullptr));
    return terrain->field->samples();
}

double hexlod_terrain_sample_bytes(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1.0);
    return double(terrain->field->byteSize());
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
    if (const char* error = terrain->field->setScale(scale)) return fail(error, -1);
    return 0;
}

double hexlod_terrain_prepare(hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, -1.0);
    if (const char* error = terrain->field->prepare()) return fail(error, -1.0);
    return double(terrain->field->missingCount());
}

double hexlod_terrain_min_height(const hexlod_terrain* terrain) {
    return terrain ? terrain->field->minHeight() : fail(kNullHandle, 0.0);
}

double hexlod_terrain_max_height(const hexlod_terrain* terrain) {
    return terrain ? terrain->field->maxHeight() : fail(kNullHandle, 0.0);
}

double hexlod_terrain_height_at(const hexlod_terrain* terrain, double x_m, double z_m) {
    return terrain ? terrain->field->heightAtPosition(x_m, z_m) : fail(kNullHandle, 0.0);
}

int32_t hexlod_grid_mesh_build(hexlod_terrain* terrain, int32_t max_cells_per_side,
                               float vertical_scale) {
    if (!terrain) return fail(kNullHandle, -1);
    if (!hexlod::buildGridMesh(*terrain->field, max_cells_per_side, vertical_scale, terrain->grid))
        return fail("max_cells_per_side must be at least 1", -1);
    return int32_t(terrain->grid.vertices.size());
}

const float* hexlod_grid_mesh_vertices(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, static_cast<const float*>(nullptr));
    return reinterpret_cast<const float*>(terrain->grid.vertices.data());
}

int32_t hexlod_grid_mesh_vertex_count(const hexlod_terrain* terrain) {
    return terrain ? int32_t(terrain->grid.vertices.size()) : fail(kNullHandle, -1);
}

const uint32_t* hexlod_grid_mesh_indices(const hexlod_terrain* terrain) {
    if (!terrain) return fail(kNullHandle, static_cast<const uint32_t*>(nullptr));
    return terrain->grid.indices.data();
}

int32_t hexlod_grid_mesh_index_count(const hexlod_terrain* terrain) {
    return terrain ? int32_t(terrain->grid.indices.size()) : fail(kNullHandle, -1);
}

} // extern "C"
