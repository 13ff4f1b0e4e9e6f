// Helpers of the hexagon mesh tests: canonical triangle sets in lattice coordinates, uniform
// refinement, and a reference 1-to-4 split.
#pragma once

#include <algorithm>
#include <array>
#include <unordered_map>
#include <vector>

#include "mesh/hex_mesh.h"
#include "mesh/hex_mesh_refine.h"

namespace hexlod::test {

using LatticeTriangle = std::array<uint64_t, 3>;

// A triangle as lattice keys, rotated so the smallest key comes first (orientation kept).
inline LatticeTriangle canonical(LatticePoint a, LatticePoint b, LatticePoint c) {
    LatticeTriangle t{latticeKey(a), latticeKey(b), latticeKey(c)};
    const size_t first = size_t(std::min_element(t.begin(), t.end()) - t.begin());
    std::rotate(t.begin(), t.begin() + first, t.end());
    return t;
}

// The mesh's drawn triangles in lattice coordinates, sorted.
inline std::vector<LatticeTriangle> latticeTriangles(const HexMesh& mesh) {
    std::vector<uint32_t> indices;
    mesh.appendTriangles(indices);
    std::vector<LatticeTriangle> out;
    for (size_t t = 0; t < indices.size(); t += 3) {
        out.push_back(canonical(mesh.vertexLattice(int32_t(indices[t])), mesh.vertexLattice(int32_t(indices[t + 1])),
                                mesh.vertexLattice(int32_t(indices[t + 2]))));
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Every live vertex's parents by a search over the whole mesh (the mesh finds them only around
// a cell, HexMesh::parentsAround): kNone for a base vertex, or where a parent is missing.
class ParentFinder {
public:
    explicit ParentFinder(const HexMesh& mesh) : mesh_(mesh) {
        for (int32_t v = 0; v < mesh.vertexCapacity(); ++v)
            if (mesh.isVertexLive(v)) at_[latticeKey(mesh.vertexLattice(v))] = v;
    }
    VertexParents operator()(int32_t v) const {
        return mesh_.parentsBy(v, [&](LatticePoint p) {
            const auto it = at_.find(latticeKey(p));
            return it == at_.end() ? kNone : it->second;
        });
    }

private:
    const HexMesh& mesh_;
    std::unordered_map<uint64_t, int32_t> at_;
};

inline LatticePoint fromKey(uint64_t key) { return {int32_t(uint32_t(key >> 32)), int32_t(uint32_t(key))}; }

// The 1-to-4 split of a triangle set: each triangle becomes its three corner triangles and the
// middle one, all keeping the orientation.
inline std::vector<LatticeTriangle> oneToFour(const std::vector<LatticeTriangle>& triangles) {
    std::vector<LatticeTriangle> out;
    for (const LatticeTriangle& t : triangles) {
        const LatticePoint a = fromKey(t[0]), b = fromKey(t[1]), c = fromKey(t[2]);
        const LatticePoint ab = latticeMidpoint(a, b), bc = latticeMidpoint(b, c), ca = latticeMidpoint(c, a);
        out.push_back(canonical(a, ab, ca));
        out.push_back(canonical(ab, b, bc));
        out.push_back(canonical(ca, bc, c));
        out.push_back(canonical(ab, bc, ca));
    }
    std::sort(out.begin(), out.end());
    return out;
}


// Merges (and so breaks) everything back, finest level first, until nothing changes.
inline void coarsenCompletely(HexMesh& mesh) {
    for (bool changed = true; changed;) {
        changed = false;
        for (int32_t level = mesh.maxLevel(); level >= 2; --level) {
            std::vector<int32_t> cells;
            for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c)) cells.push_back(c);
            for (int32_t c : cells)
                if (mesh.isLive(c) && mesh.cell(c).level == level && mesh.merge(c)) changed = true;
        }
    }
}

} // namespace hexlod::test
