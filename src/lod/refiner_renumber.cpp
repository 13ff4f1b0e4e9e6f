// The refiner follows a renumbering of the mesh (HexMesh::compact, after the mesh shrank by a
// sixteenth): its per-cell records, cached bounds (§5.1), states, fading merges (§7) and
// queued cells move with their cells. See refiner.h.
#include "lod/refiner.h"

#include <algorithm>

namespace hexlod {

void Refiner::renumber(const std::vector<int32_t>& cellMap, const std::vector<int32_t>& vertexMap) {
    const size_t cells = size_t(mesh_->cellCapacity());
    // The sweep goes on from the group of the first kept cell at or after where it stopped.
    int32_t cursor = 0;
    for (size_t c = size_t(std::max(sweepCursor_, 0)) * SweepSummaries::kGroup; c < cellMap.size(); ++c) {
        if (cellMap[c] != kNone) {
            cursor = cellMap[c];
            break;
        }
    }
    sweepCursor_ = SweepSummaries::groupOf(cursor);
    const size_t room = mesh_->cellPoolRoom(); // the records' arrays keep the pool's room
    cache_.renumber(cellMap, cells, room);
    renumberPool(records_, cellMap, cells, room);
    renumberPool(state_, cellMap, cells, room);
    if (field_->tiles()) renumberPool(starved_, cellMap, cells, room);
    summaries_.release(); // every group read again
    summaries_.resize(cells, room);
    // A merge whose cell or vertex is gone (the mesh changed around it in the last update) is
    // called off by the next update, as it would have been without the renumbering.
    pending_.renumber(cellMap, vertexMap);
    // Cells queued for the next update; a freed cell is gone with its record.
    for (std::vector<int32_t>* list : {&changes_, &fresh_, &mergeList_, &capChains_}) {
        size_t kept = 0;
        for (int32_t c : *list)
            if (size_t(c) < cellMap.size() && cellMap[size_t(c)] != kNone) (*list)[kept++] = cellMap[size_t(c)];
        list->resize(kept);
    }
    size_t kept = 0;
    for (const Candidate& candidate : heap_)
        if (cellMap[size_t(candidate.cell)] != kNone) heap_[kept++] = {candidate.pixels, cellMap[size_t(candidate.cell)]};
    heap_.resize(kept);
    std::make_heap(heap_.begin(), heap_.end(), lowerPriority);
}

} // namespace hexlod
