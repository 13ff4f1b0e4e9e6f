// Caching of refinement data (paper §5.1): "we cache the refinement data for the previous
// levels [...]. If a hexagon is merged the refinement data of the higher level is kept, as
// well, for a possible later refinement."
//
// hexlod keeps one entry per cell record (40 bytes): the cell's own bound (§5, cell_bounds.h)
// and slope box, and its parent's bound, the cell a merge would make. The refiner carries them
// across operations: a split keeps the split cell's own bound as the parent bound of the record
// that stays, and a merge makes the parent bound the merged cell's own (refiner.cpp,
// refineStep and mergeNow). Any other change of a record invalidates its entry; a bound is
// recomputed from the samples only when a test needs it.
#pragma once

#include <cstdint>
#include <vector>

#include "lod/cell_bounds.h"
#include "mesh/pool_growth.h"

namespace hexlod {

class RefinementCache {
public:
    /// A bound not computed yet: a negative error, so an entry needs no flags (40 bytes).
    static constexpr CellError kUnknown{0.0f, 0.0f, -1.0f};
    static bool known(const CellError& e) { return e.error >= 0.0f; }

    struct Entry {
        CellError own = kUnknown;    // the cell's bound
        SlopeBox ownSlopes;          // the slopes under it (back-face culling), valid with own
        CellError parent = kUnknown; // the bound of the cell a merge makes
    };
    static_assert(sizeof(Entry) == 40, "issue 12 counts the bytes of a cell");

    /// One entry per cell record: grows with the mesh's cell pool.
    void grow(size_t records) {
        if (entries_.size() >= records) return;
        reserveForPool(entries_, records);
        entries_.resize(records);
    }
    /// No entries (a new mesh): they grow again with its pool.
    void clear() { releasePool(entries_); }
    /// The mesh renumbered its records (HexMesh::compact): entries follow their records.
    void renumber(const std::vector<int32_t>& map, size_t records) { renumberPool(entries_, map, records); }
    /// The record changed in a way the carry-over rules do not cover.
    void invalidate(int32_t record) { entries_[size_t(record)] = Entry{}; }

    Entry& operator[](size_t record) { return entries_[record]; }
    const Entry& operator[](size_t record) const { return entries_[record]; }
    size_t size() const { return entries_.size(); }
    size_t memoryBytes() const { return entries_.capacity() * sizeof(Entry); }

private:
    std::vector<Entry> entries_;
};

} // namespace hexlod
