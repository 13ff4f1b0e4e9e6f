// Merges waiting for their vertices to fade out (paper §7); see pending_merges.h.
#include "lod/pending_merges.h"

#include <algorithm>

namespace hexlod {

void PendingMerges::begin(HexMesh& mesh, VertexFades& fades, int32_t cell) {
    Merge merge{cell, 0, {}};
    freed_.clear();
    mesh.verticesFreedByMerge(cell, freed_);
    for (int32_t v : freed_) {
        merge.vertices[merge.count++] = v;
        fades.blendOut(mesh, v, mesh.parentsAround(v, cell));
    }
    merges_.push_back(merge);
}

bool PendingMerges::stillFrees(const HexMesh& mesh, const Merge& merge) {
    if (merge.cell == kNone || !mesh.canMerge(merge.cell)) return false; // kNone: gone (renumber)
    freed_.clear();
    mesh.verticesFreedByMerge(merge.cell, freed_);
    return std::equal(freed_.begin(), freed_.end(), merge.vertices, merge.vertices + merge.count);
}

void PendingMerges::cancelFades(HexMesh& mesh, VertexFades& fades, const Merge& merge) {
    for (int32_t i = 0; i < merge.count; ++i)
        if (merge.vertices[i] != kNone && mesh.isVertexLive(merge.vertices[i])) fades.cancelBlendOut(mesh, merge.vertices[i]);
}

bool PendingMerges::fadedOut(HexMesh& mesh, VertexFades& fades, const Merge& merge) {
    bool faded = true;
    for (int32_t k = 0; k < merge.count; ++k) {
        const StreamVertex& v = mesh.streamVertex(merge.vertices[k]);
        if (!fades.blendingOut(v)) // reversed by a called-off merge
            fades.blendOut(mesh, merge.vertices[k], mesh.parentsAround(merge.vertices[k], merge.cell));
        faded = faded && fades.fadedOut(v);
    }
    return faded;
}

void PendingMerges::renumber(const std::vector<int32_t>& cellMap, const std::vector<int32_t>& vertexMap) {
    for (Merge& merge : merges_) {
        merge.cell = cellMap[size_t(merge.cell)];
        for (int32_t k = 0; k < merge.count; ++k) merge.vertices[k] = vertexMap[size_t(merge.vertices[k])];
    }
}

} // namespace hexlod
