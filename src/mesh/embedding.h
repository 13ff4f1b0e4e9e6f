// Where a lattice point goes in space: the lattice embedding (paper §4.7), one small,
// swappable function.
//
// - Shifted (the paper's): odd rows move half a sample east, so hexagons are nearly
//   equilateral; an odd-row vertex takes the mean of the two samples it sits between. Vertices
//   of every level coarser than the finest lie on even rows, i.e. on real samples; at the
//   finest level the shift smooths odd rows by |second difference|/4.
// - Exact: the same topology, but every vertex sits on the sample it indexes (column j of an
//   odd row at x = j). Straight left and right edges, no interpolated heights, zero error at
//   full refinement. Its new vertices are not midpoints of their parents' edges.
//
// Lookups outside the field are clamped: the lattice may extend past the rectangle (§4.7 and
// docs in hex_mesh_domain.cpp), and what lies outside is hidden when drawing.
#pragma once

#include <glm/vec3.hpp>

#include "field/heightfield.h"
#include "mesh/lattice.h"

namespace hexlod {

enum class Embedding : int32_t { Shifted = 0, Exact = 1 };

/// Position in metres (x east, y up = height, z south) of a lattice point.
glm::vec3 embedLatticePoint(const Heightfield& field, Embedding embedding, LatticePoint p);

/// Whether a lattice point's height comes from a no-data sample (Heightfield::sampleMissing):
/// its sample, or on a shifted odd row either of the two it sits between.
bool latticePointMissing(const Heightfield& field, Embedding embedding, LatticePoint p);

/// The fixed rule for an interior semi-hexagon's two-triangle fan (§7 says "an arbitrary
/// corner", which changes the surface): corners a, b, c, d counter-clockwise, fanned from a
/// unless fanning from b gives a larger smallest triangle in the embedding's ground plane.
/// In the shifted embedding the trapezoid is symmetric and a is kept; in the exact one a
/// sheared trapezoid may have three corners in one column, and b avoids the flat triangle.
bool semiFanFromSecondCorner(Embedding embedding, LatticePoint a, LatticePoint b, LatticePoint c, LatticePoint d);

} // namespace hexlod
