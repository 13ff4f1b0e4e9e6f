// Simple refinement drivers over the hexagon mesh operations, for tests and benchmarks: the
// uniform split (Fig. 4) and a local refinement around a point. View-dependent refinement
// (§5, §6) is refiner.h.
#pragma once

#include <cstdint>

#include "mesh/hex_mesh.h"

namespace hexlod {

/// Splits every whole cell of the coarsest remaining level, `rounds` times: after round n the
/// mesh is n 1-to-4 splits of the base triangulation. Returns the number of splits.
int64_t refineUniformly(HexMesh& mesh, int32_t rounds);

/// Refines, `rounds` times, every cell whose centre lies within radius metres (horizontally)
/// of (x, z): whole cells are split, semi-hexagons joined by splitting the cell across their
/// long edge (or joined with their partner). Returns the number of splits, forced ones included.
int64_t refineNear(HexMesh& mesh, double x, double z, double radius, int32_t rounds);

} // namespace hexlod
