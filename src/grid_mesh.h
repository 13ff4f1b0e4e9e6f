// GridMesh: an interim, non-adaptive mesh of a height field, subsampled on a regular grid.
// It proves the chain file -> core -> WebGL2 until the hexagon mesh (paper §4) replaces it.
#pragma once

#include <cstdint>
#include <vector>

#include "heightfield.h"

namespace hexlod {

/// Vertex layout shared with the renderer: position in metres (x east, y up, z south) and a
/// unit normal, 6 floats.
struct MeshVertex {
    float x, y, z;
    float nx, ny, nz;
};

struct GridMesh {
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices; // triangle list, counter-clockwise seen from +y
};

/// Builds a grid through every step-th sample, always including the last row and column so
/// the whole field is covered. The step is the smallest that keeps at most maxCellsPerSide
/// cells along each side. Heights are multiplied by verticalScale.
/// Returns false (mesh left empty) when maxCellsPerSide < 1.
bool buildGridMesh(const Heightfield& field, int32_t maxCellsPerSide, float verticalScale,
                   GridMesh& mesh);

} // namespace hexlod
