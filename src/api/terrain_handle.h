// What a hexlod_terrain handle is, shared by the two ABI files (hexlod_api.cpp,
// hexlod_diagnostics_api.cpp), and their one error convention. Not a public header.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "api/hexlod.h"
#include "diagnostics/popping_meter.h"
#include "terrain.h"

struct hexlod_terrain {
    std::unique_ptr<hexlod::Terrain> core;
    hexlod::PoppingMeter popping; // diagnostics only; unused by the product
    std::vector<hexlod_tile_want> wants; // what hexlod_terrain_tile_wants hands out
};

namespace hexlod::api {

constexpr const char* kNullHandle = "the terrain handle is NULL (create it with hexlod_terrain_create)";
constexpr const char* kNoMesh = "the terrain has no hexagon mesh yet (call hexlod_terrain_reset_mesh)";

/// Records `message` for hexlod_last_error().
void setError(const char* message);

/// Records a failure and returns HEXLOD_ERROR (or the null pointer the caller returns).
inline int32_t fail(const char* message) {
    setError(message);
    return HEXLOD_ERROR;
}

/// Null (after recording why) when the handle is null or has no mesh.
inline const char* needMesh(const hexlod_terrain* terrain) {
    if (!terrain) return kNullHandle;
    if (!terrain->core->hasMesh()) return kNoMesh;
    return nullptr;
}

} // namespace hexlod::api
