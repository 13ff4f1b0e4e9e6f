// StreamVertex: one vertex of the hexagon mesh exactly as the renderer draws it. Paper §7:
// vertex data exists once. HexMesh owns the pool and writes positions, FanStream writes the
// normals, Geomorph the blend; the renderer uploads the pool as it is (28 bytes a vertex).
// A blend is vertical (geomorph.h): its start differs from the position only in height, so the
// start is one float, not a point (issue 12: 8 bytes a vertex less).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace hexlod {

struct StreamVertex {
    glm::vec3 position;  // metres: x east, y height (unscaled: the shader applies the exaggeration), z south
    int16_t normal[4];   // unit normal as snorm16 x, y, z (w = 0), averaged over the adjacent triangles
    float morphFromHeight; // metres (unscaled): the height where the geomorph blend starts, the coarser surface under the vertex
    float morphKey;        // 0: not blending; f+1: blending in since frame f; -(f+1): blending out since frame f
};
static_assert(sizeof(StreamVertex) == 28, "the renderer's attribute layout assumes 28 bytes");

/// Floats (4-byte words) per StreamVertex, for code that reads the pool as a float array.
constexpr int32_t kStreamVertexWords = int32_t(sizeof(StreamVertex) / 4);

} // namespace hexlod
