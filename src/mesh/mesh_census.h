// How many live cells of each kind the hexagon mesh has (paper §4.2: full hexagons, interior
// semi-hexagons, boundary semi-hexagons), for the viewer's HUD. A pass over the cell pool.
#pragma once

#include <array>

#include "mesh/hex_mesh.h"

namespace hexlod {

/// Live cells indexed by CellKind: [Full, Semi, BoundarySemi].
inline std::array<int32_t, 3> countCellKinds(const HexMesh& mesh) {
    std::array<int32_t, 3> counts{0, 0, 0};
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c)
        if (mesh.isLive(c)) ++counts[size_t(mesh.cell(c).kind)];
    return counts;
}

} // namespace hexlod
