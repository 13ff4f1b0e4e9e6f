// Caching of refinement data (paper §5.1): "we cache the refinement data for the previous
// levels [...]. If a hexagon is merged the refinement data of the higher level is kept, as
// well, for a possible later refinement."
//
// hexlod keeps one entry per cell record (20 bytes, packed_bounds.h): the cell's own bound
// (§5, cell_bounds.h) and slope box, and its parent's bound, the cell a merge would make. The
// refiner carries them across operations: a split keeps the split cell's own bound as the
// parent bound of the record that stays, and a merge makes the parent bound the merged cell's
// own (refiner.cpp, refineStep and mergeNow); a joined hexagon's slot keeps the half a merge
// test bounded, which the merge then makes the own bound of that semi-hexagon. Carried bounds
// move packed, so they never loosen on the way. Any other change of a record invalidates its
// entry; a bound is recomputed from the samples only when a test needs it. What a test sees
// is always the unpacked bound, also right after it was computed, so a decision does not
// depend on whether a bound was cached.
#pragma once

#include <cstdint>
#include <vector>

#include "lod/cell_bounds.h"
#include "lod/packed_bounds.h"
#include "mesh/pool_growth.h"

namespace hexlod {

class RefinementCache {
public:
    struct Entry {
        PackedBound own;       // the cell's bound
        PackedBound parent;    // the bound of the cell a merge makes
        PackedSlopes ownSlopes; // the slopes under the cell (back-face culling): computed when a test needs them
    };
    static_assert(sizeof(Entry) == 20, "the memory per drawn triangle counts the bytes of a cell");

    /// The field's height range, which the packed heights are steps of (before any entry).
    void setHeightRange(float lowest, float highest) { packing_.setHeightRange(lowest, highest); }

    /// One entry per cell record: grows with the mesh's cell pool (of `room` records).
    void grow(size_t records, size_t room) {
        if (entries_.size() >= records) return;
        reserveLikePool(entries_, records, room);
        entries_.resize(records);
    }
    /// No entries (a new mesh): they grow again with its pool.
    void clear() { releasePool(entries_); }
    /// The mesh renumbered its records (HexMesh::compact): entries follow their records.
    void renumber(const std::vector<int32_t>& map, size_t records, size_t room) { renumberPool(entries_, map, records, room); }
    /// The record changed in a way the carry-over rules do not cover.
    void invalidate(int32_t record) { entries_[size_t(record)] = Entry{}; }

    bool hasOwn(int32_t record) const { return BoundPacking::known(entries_[size_t(record)].own); }
    bool hasParent(int32_t record) const { return BoundPacking::known(entries_[size_t(record)].parent); }
    CellError own(int32_t record) const { return packing_.unpack(entries_[size_t(record)].own); }
    CellError parent(int32_t record) const { return packing_.unpack(entries_[size_t(record)].parent); }
    /// Unknown (never back-facing) when not computed yet.
    SlopeBox ownSlopes(int32_t record) const { return BoundPacking::unpack(entries_[size_t(record)].ownSlopes); }
    bool hasOwnSlopes(int32_t record) const { return entries_[size_t(record)].ownSlopes.computed(); }

    /// The own bound; its slopes are not computed yet.
    void setOwn(int32_t record, const CellError& own) {
        entries_[size_t(record)].own = packing_.pack(own);
        entries_[size_t(record)].ownSlopes = PackedSlopes::notComputed();
    }
    void setOwnSlopes(int32_t record, const SlopeBox& slopes) { entries_[size_t(record)].ownSlopes = BoundPacking::pack(slopes); }
    void setParent(int32_t record, const CellError& parent) { entries_[size_t(record)].parent = packing_.pack(parent); }

    /// The carry-overs, packed as they are.
    PackedBound packedOwn(int32_t record) const { return entries_[size_t(record)].own; }
    PackedBound packedParent(int32_t record) const { return entries_[size_t(record)].parent; }
    void setPackedParent(int32_t record, const PackedBound& parent) { entries_[size_t(record)].parent = parent; }
    void setPackedOwn(int32_t record, const PackedBound& own) {
        entries_[size_t(record)].own = own;
        entries_[size_t(record)].ownSlopes = PackedSlopes::notComputed();
    }

    /// A joined hexagon (split counter 0) has no parent to cache: its parent slot keeps the bound
    /// of one of its halves instead, the semi-hexagon that a merge of the cell across from it
    /// would leave (Refiner::halvesVerdict), so a merge test that comes back to it does not scan
    /// the half again. The error's sign bit (errors are never negative) tells which half: 0 the
    /// one from the break diameter's first corner, 1 the other. Any change of the hexagon
    /// (a split gives it a split counter) invalidates the entry like every change.
    bool hasHalf(int32_t record, int32_t which) const {
        const PackedBound& b = entries_[size_t(record)].parent;
        return BoundPacking::known(b) && (b.error >> 15) == uint16_t(which);
    }
    CellError half(int32_t record) const { return packing_.unpack(packedHalf(record)); }
    PackedBound packedHalf(int32_t record) const {
        PackedBound b = entries_[size_t(record)].parent;
        b.error &= 0x7FFFu;
        return b;
    }
    void setHalf(int32_t record, int32_t which, const CellError& half) {
        PackedBound b = packing_.pack(half);
        b.error = uint16_t(b.error | uint16_t(which) << 15);
        entries_[size_t(record)].parent = b;
    }

    /// Asks for a record's entry ahead of its use (a hint; nothing changes).
    void prefetch(int32_t record) const { __builtin_prefetch(&entries_[size_t(record)]); }

    size_t size() const { return entries_.size(); }
    size_t memoryBytes() const { return entries_.capacity() * sizeof(Entry); }

private:
    BoundPacking packing_;
    std::vector<Entry> entries_;
};

} // namespace hexlod
