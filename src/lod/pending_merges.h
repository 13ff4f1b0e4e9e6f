// Merges that wait for their vertices to fade out (paper §7: "inverse blending is triggered by
// a merge [...], which [is] finished when the vertex has faded out"). A merge wanted under
// geomorphing starts here: the vertices it will free begin to fade (vertex_fades.h), and the
// refiner merges once they have faded, or calls the merge off when the mesh around it changed
// or the view wants the detail back (Refiner::advancePendingMerges).
#pragma once

#include <cstdint>
#include <vector>

#include "lod/vertex_fades.h"
#include "mesh/hex_mesh.h"

namespace hexlod {

class PendingMerges {
public:
    /// One merge and the vertices it frees, fading out.
    struct Merge {
        int32_t cell;
        int32_t count;
        int32_t vertices[12]; // six corners and up to six centres of the ring cells it breaks
    };

    /// Starts fading out the vertices a merge of `cell` frees (HexMesh::canMerge allows it).
    void begin(HexMesh& mesh, VertexFades& fades, int32_t cell);
    /// Whether the merge is still allowed and would free exactly the vertices that are fading.
    bool stillFrees(const HexMesh& mesh, const Merge& merge);
    /// Reverses the fades of a merge that is called off (its vertices still live).
    static void cancelFades(HexMesh& mesh, VertexFades& fades, const Merge& merge);
    /// Whether every vertex of the merge has faded out. A fade that a called-off merge
    /// reversed (the vertices are shared) starts again.
    static bool fadedOut(HexMesh& mesh, VertexFades& fades, const Merge& merge);

    /// Keeps the merges for which keep(merge) is true, in their order. keep may change the
    /// mesh and call stillFrees, not begin a merge.
    template <typename Keep>
    void keepIf(Keep&& keep) {
        size_t kept = 0;
        for (size_t i = 0; i < merges_.size(); ++i) {
            const Merge merge = merges_[i];
            if (keep(merge)) merges_[kept++] = merge;
        }
        merges_.resize(kept);
    }
    const std::vector<Merge>& merges() const { return merges_; }
    int32_t size() const { return int32_t(merges_.size()); }
    void clear() { merges_.clear(); }

    /// The mesh renumbered its cells and vertices (HexMesh::compact). A merge whose cell or
    /// vertex is gone keeps kNone for it: it is called off at the next update.
    void renumber(const std::vector<int32_t>& cellMap, const std::vector<int32_t>& vertexMap);
    size_t memoryBytes() const { return merges_.capacity() * sizeof(Merge) + freed_.capacity() * sizeof(int32_t); }
    size_t liveMemoryBytes() const { return merges_.size() * sizeof(Merge); }

private:
    std::vector<Merge> merges_;
    std::vector<int32_t> freed_; // HexMesh::verticesFreedByMerge's answer, reused
};

} // namespace hexlod
