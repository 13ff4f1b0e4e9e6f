// StreamVertex: one vertex of the hexagon mesh exactly as the renderer draws it. Paper §7:
// vertex data exists once. HexMesh owns the pool and writes positions, Geomorph writes the
// blend; the renderer uploads the pool as it is (20 bytes a vertex). A blend is vertical
// (geomorph.h): its start differs from the position only in height, so the start is one
// float, not a point. The mesh's vertex normals are the fan stream's own array, kept only while
// the page draws them (36 -> 20 bytes a vertex).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace hexlod {

struct StreamVertex {
    glm::vec3 position;    // metres: x east, y height (unscaled: the shader applies the exaggeration), z south
    float morphFromHeight; // metres (unscaled): the height where the geomorph blend starts, the coarser surface under the vertex
    float morphKey;        // 0: not blending; f+1: blending in since frame f; -(f+1): blending out since frame f
};
static_assert(sizeof(StreamVertex) == 20, "the renderer's attribute layout assumes 20 bytes");

/// Floats (4-byte words) per StreamVertex, for code that reads the pool as a float array.
constexpr int32_t kStreamVertexWords = int32_t(sizeof(StreamVertex) / 4);

} // namespace hexlod
