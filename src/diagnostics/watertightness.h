// Watertightness of what the renderer draws (paper §7: the fan stream), checked from the index
// and vertex arrays alone, independently of the mesh's own invariants (§4, checkInvariants):
// the triangles the GPU assembles from the indices (primitive restart at 0xFFFFFFFF) must tile
// one disc with no T-junction or crack. A T-junction (a vertex on another triangle's edge)
// leaves that edge used by one triangle and the two edges along it by one each: a second
// boundary loop, which this check reports.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace hexlod {

/// How the GPU assembles an index array (both with primitive restart).
enum class Primitive { TriangleFan, Triangles };

/// Appends the triangles (index triples) the GPU assembles from `indices` as `primitive` with
/// primitive restart: a restart index starts a new fan, or drops an unfinished triangle.
void assembleTriangles(const uint32_t* indices, size_t count, Primitive primitive, std::vector<uint32_t>& out);

struct WatertightStats {
    int64_t triangles = 0;
    int64_t vertices = 0;      // distinct vertices the triangles use
    int64_t edges = 0;         // undirected
    int64_t boundaryEdges = 0; // used by one triangle
    int64_t boundaryLoops = 0;
    int64_t euler = 0;         // vertices - edges + triangles: 1 for a disc
    const char* error = nullptr; // what is wrong (static storage until the next failed check), or null
};

/// Checks that `triangles` (index triples into positions: x, y, z floats, `strideWords` floats
/// apart, `vertexCount` of them; y up, x east, z south) form a watertight surface over one disc:
/// - every index names a vertex below vertexCount that `live` accepts (when given), at a finite position;
/// - every triangle turns counter-clockwise seen from +y, with a non-zero area;
/// - every directed edge is used once (so an interior edge by exactly two triangles, in opposite
///   directions), the edges used once form exactly one loop through distinct vertices, and the
///   Euler characteristic is 1 (no holes, cracks, T-junctions, or pieces apart).
/// Allocates; for tests and benchmarks.
WatertightStats checkWatertight(const std::vector<uint32_t>& triangles, const float* positions, size_t vertexCount, size_t strideWords,
                                const std::function<bool(uint32_t)>& live = nullptr);

} // namespace hexlod
