// Which tiles stay held; see tile_residency.h.
#include "lod/tile_residency.h"

#include <algorithm>

namespace hexlod {

void TileResidency::fitLevels(const SampleTiles& tiles) {
    if (lastUse_.size() == size_t(tiles.levelCount())) return;
    lastUse_.assign(size_t(tiles.levelCount()), {});
    for (int32_t l = 0; l < tiles.levelCount(); ++l) lastUse_[size_t(l)].reset(tiles.level(l).tilesAcross, tiles.level(l).tilesDown, 0u);
}

uint32_t& TileResidency::lastUse(int32_t level, int32_t tx, int32_t ty) {
    return lastUse_[size_t(level)].at(tx, ty);
}

void TileResidency::arrived(const SampleTiles& tiles, int32_t level, int32_t tx, int32_t ty) {
    fitLevels(tiles);
    lastUse(level, tx, ty) = now_;
}

double TileResidency::heldBytes(const SampleTiles& tiles) const {
    const TileLevel& top = tiles.level(tiles.coarsest());
    return double(tiles.sampleBytes()) - double(top.tileCount()) * double(tiles.slotBytes());
}

int32_t TileResidency::keepWithinCap(SampleTiles& tiles, const std::vector<TileWant>& inUse, SampleRect& changed) {
    fitLevels(tiles);
    for (const TileWant& t : inUse) lastUse(t.level, t.tx, t.ty) = now_;
    candidates_.clear();
    for (int32_t s = 0; s < tiles.slotCount(); ++s) {
        const TileId& t = tiles.heldTile(s);
        if (t.level < 0 || t.level >= tiles.coarsest() || !tiles.present(t.level, t.tx, t.ty)) continue;
        const uint32_t use = lastUse_[size_t(t.level)].get(t.tx, t.ty);
        if (use != now_) candidates_.push_back({use, t.level, t.tx, t.ty});
    }
    // Oldest use first; among tiles last used together, the finer first (a coarser tile serves
    // more of the view), then in reading order so the choice never depends on anything else.
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
        if (a.lastUse != b.lastUse) return a.lastUse < b.lastUse;
        if (a.level != b.level) return a.level < b.level;
        return a.ty != b.ty ? a.ty < b.ty : a.tx < b.tx;
    });
    int32_t count = 0;
    for (const Candidate& c : candidates_) {
        if (!overCap(tiles)) break;
        if (tiles.evict(c.level, c.tx, c.ty, changed)) ++count;
    }
    evictions_ += count;
    return count;
}

size_t TileResidency::memoryBytes() const {
    size_t bytes = candidates_.capacity() * sizeof(Candidate);
    for (const auto& uses : lastUse_) bytes += uses.memoryBytes();
    return bytes;
}

} // namespace hexlod
