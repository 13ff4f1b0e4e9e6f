// The triangular lattice under the hexagon mesh (paper §4, §4.7).
//
// Lattice points use axial coordinates (q, r): r is the sample row (south, +z) and the row is
// a lattice line; the paper's layout shifts odd rows by half a sample, so the point's
// horizontal lattice position is q + r/2, and its sample column is j = q + floor(r/2).
//
// Resolution k of a mesh whose base step is S = 2^K has step s = S >> k: its vertices are the
// points whose q and r are multiples of s, and a vertex is a hexagon centre at that resolution
// when (q/s - r/s) mod 3 == 0 (a 3-colouring of the lattice: every triangle has exactly one
// centre). The colouring is the same at every resolution, which is what makes a uniform
// hexagon split equal to the 1-to-4 split (Fig. 4): the new centres are the old centres plus
// the midpoints of the old hexagons' edges.
#pragma once

#include <cstdint>

namespace hexlod {

struct LatticePoint {
    int32_t q = 0;
    int32_t r = 0;
    friend bool operator==(LatticePoint a, LatticePoint b) { return a.q == b.q && a.r == b.r; }
    friend bool operator!=(LatticePoint a, LatticePoint b) { return !(a == b); }
};

/// The six corner directions of a hexagon, counter-clockwise seen from +y (x east, z south):
/// east, north-east, north-west, west, south-west, south-east. Corner slot k (1..6) of a
/// hexagon with centre c and step s sits at c + s * kDirections[k - 1].
constexpr LatticePoint kDirections[6] = {{1, 0}, {1, -1}, {0, -1}, {-1, 0}, {-1, 1}, {0, 1}};

inline LatticePoint latticeAdd(LatticePoint p, LatticePoint d, int32_t s) {
    return {p.q + s * d.q, p.r + s * d.r};
}

inline LatticePoint latticeMidpoint(LatticePoint a, LatticePoint b) {
    return {(a.q + b.q) / 2, (a.r + b.r) / 2};
}

inline int32_t floorDiv2(int32_t v) { return v >= 0 ? v / 2 : -((1 - v) / 2); }

/// Sample column of a lattice point.
inline int32_t sampleColumn(LatticePoint p) { return p.q + floorDiv2(p.r); }

inline int32_t positiveMod3(int32_t v) { return ((v % 3) + 3) % 3; }

/// Whether p is a vertex of the resolution with step s, and a hexagon centre there.
inline bool isCenterAtStep(LatticePoint p, int32_t s) {
    if (p.q % s != 0 || p.r % s != 0) return false;
    return positiveMod3(p.q / s - p.r / s) == 0;
}

/// A 64-bit key of a lattice point, for hashing and sorting.
inline uint64_t latticeKey(LatticePoint p) {
    return (uint64_t(uint32_t(p.q)) << 32) | uint64_t(uint32_t(p.r));
}

/// Twice the signed area of triangle abc in lattice units (row spacing taken as 1), positive
/// when abc turns counter-clockwise seen from +y. Exact in integers.
inline int64_t latticeDoubleArea(LatticePoint a, LatticePoint b, LatticePoint c) {
    // Horizontal lattice position doubled: X = 2q + r; rows grow southwards, so a
    // counter-clockwise turn seen from above has a negative (X, r) cross product.
    const int64_t abx = int64_t(2 * (b.q - a.q) + (b.r - a.r)), abr = b.r - a.r;
    const int64_t acx = int64_t(2 * (c.q - a.q) + (c.r - a.r)), acr = c.r - a.r;
    return -(abx * acr - abr * acx);
}

} // namespace hexlod
