// TileResidency: which tiles of a field that arrives by tiles (field/sample_tiles.h) stay held.
// The core is the one owner of its tiles: it stores them, knows which ones the drawn mesh
// stands on, and lets tiles go when the held ones pass a byte cap, least recently used first
// and never one the mesh stands on (letting that go would pull the mesh there back to a coarser
// level, and the view would ask for it again at once). The caller only fetches what the view
// wants (lod/tile_wants.h) and hands it in.
//
// "Used" is learnt where it costs nothing extra: a tile is used when it arrives, and again at
// every pass that finds the mesh standing on it. A pass (one walk over the live cells) runs
// only in a frame whose stream step finds the tiles over the cap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "field/sample_tiles.h"
#include "field/sparse_grid.h"
#include "lod/tile_wants.h"

namespace hexlod {

class TileResidency {
public:
    /// Bytes of samples the tiles past the coarsest level may hold (the coarsest level is held
    /// whole and not counted). Unlimited until set; a smaller cap lets tiles go at the next pass.
    void setCapBytes(double bytes) { capBytes_ = bytes; }
    double capBytes() const { return capBytes_; }

    /// The tile was committed: it counts as used now.
    void arrived(const SampleTiles& tiles, int32_t level, int32_t tx, int32_t ty);
    /// One frame passed (the clock the uses are stamped with).
    void tick() { ++now_; }

    /// Bytes of samples in the tiles held past the coarsest level.
    double heldBytes(const SampleTiles& tiles) const;
    bool overCap(const SampleTiles& tiles) const { return heldBytes(tiles) > capBytes_; }

    /// Marks the tiles in `inUse` (TileWants::collectInUse) as used now, then lets the least
    /// recently used of the others go until the held bytes fit the cap (the tiles in use may
    /// exceed it alone: they stay). `changed` grows as for SampleTiles::evict. Returns how many
    /// tiles went.
    int32_t keepWithinCap(SampleTiles& tiles, const std::vector<TileWant>& inUse, SampleRect& changed);

    /// Tiles let go so far.
    int64_t evictions() const { return evictions_; }
    size_t memoryBytes() const;

private:
    struct Candidate {
        uint32_t lastUse;
        int32_t level, tx, ty;
    };
    void fitLevels(const SampleTiles& tiles);
    uint32_t& lastUse(int32_t level, int32_t tx, int32_t ty);

    double capBytes_ = std::numeric_limits<double>::infinity();
    uint32_t now_ = 1;
    int64_t evictions_ = 0;
    std::vector<SparseGrid<uint32_t>> lastUse_; // per level and tile: the frame of its last known use
    std::vector<Candidate> candidates_;          // reused across passes
};

} // namespace hexlod
