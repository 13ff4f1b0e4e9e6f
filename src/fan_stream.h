// FanStream: the arrays the renderer uploads (paper §7). Every vertex of the mesh once, with a
// normal averaged from its adjacent triangles of the current mesh, and every cell as one
// triangle fan closed by the primitive-restart index:
//   full hexagon:          centre, six corners, first corner again   (6 triangles)
//   boundary semi-hexagon: centre, its four corners                  (3 triangles, §4.2)
//   interior semi-hexagon: its four corners from the first one       (2 triangles)
// Fans are grouped by level, ascending, so a level can be drawn as one range.
#pragma once

#include <cstdint>
#include <vector>

#include "hex_mesh.h"

namespace hexlod {

constexpr uint32_t kRestartIndex = 0xFFFFFFFFu; // WebGL2's fixed primitive-restart index

/// Floats per streamed vertex: position x, y, z in metres (y times the vertical scale) and a
/// unit normal.
constexpr int32_t kFloatsPerVertex = 6;

struct FanStream {
    std::vector<float> vertices;       // kFloatsPerVertex per vertex slot of the mesh pool
    std::vector<uint32_t> indices;     // fans separated by kRestartIndex
    std::vector<uint32_t> outline;     // line pairs: every cell edge once (hexagon outlines), if withOutline
    std::vector<int32_t> levelOffsets; // first index of each level's fans; one more entry at the end
    int32_t vertexCount = 0;           // vertex slots written (the pool's capacity)
    bool withOutline = false;          // write the outline too (the wireframe view)
};

/// Writes the mesh's vertices, fans and outlines into the stream. The vectors only grow.
void buildFanStream(const HexMesh& mesh, float verticalScale, FanStream& stream);

} // namespace hexlod
