// MinMaxPyramid: the lowest and highest height over blocks of samples, and over blocks of
// blocks, built once at load (one pass over the samples). It bounds the heights under a
// large cell without scanning its samples (paper §5.1 scans them; a 16k field's base cells
// would hold hundreds of millions).
//
// A field that arrives by tiles (field/sample_tiles.h) may be far larger than memory, and so
// would be a pyramid over all of it (67 MB at 40000², 420 MB at 100000²). Its levels of blocks
// under kChunk samples a side are kept only for the chunks (kChunk² samples) whose heights are
// all at full resolution, so they grow with the tiles held, not with the field; elsewhere those
// blocks are measured from the coarser samples when asked (few, since the heights there come
// from an overview). The bounds are the same as a whole field's once the tiles are in.
#pragma once

#include <cstdint>
#include <vector>

#include "field/heightfield.h"

namespace hexlod {

class MinMaxPyramid {
public:
    static constexpr int32_t kBlock = 16;  // samples per block side at the finest level
    static constexpr int32_t kChunk = 256; // a tiled field's blocks this size and up are kept for all of it
    /// The block side in use.
    int32_t block() const { return kBlock; }

    /// One pass over the field's samples (a tiled field: over the levels its heights come
    /// from, SampleTiles::range).
    void build(const Heightfield& field);
    /// The heights of a tiled field changed in `rect`: its blocks and the blocks above them
    /// are measured again.
    void update(const Heightfield& field, const SampleRect& rect);

    /// Lowest and highest height in metres of the samples with column in [j0, j1] and row in
    /// [i0, i1] (clamped to the field; inclusive). The result may cover a few more samples
    /// than asked (whole blocks), so it is a conservative bound.
    void query(int32_t j0, int32_t i0, int32_t j1, int32_t i1, float& low, float& high) const;

    size_t memoryBytes() const;

private:
    struct Level {
        int32_t columns = 0, rows = 0; // blocks
        std::vector<float> low, high;
    };
    // A tiled field's levels under kChunk, per chunk: blocks of 16, 32, 64 and 128 samples.
    static constexpr int32_t kFineLevels = 4;
    static constexpr int32_t kChunkSide = kChunk / kBlock; // finest blocks across a chunk
    static_assert(kChunkSide >> kFineLevels == 1, "the fine levels end one level under the chunk");
    // Where each fine level starts among a chunk's blocks, and their count: 16², 8², 4², 2².
    static constexpr int32_t kFineOffset[kFineLevels] = {0, 256, 320, 336};
    static constexpr int32_t kChunkBlocks = 340;

    void mergeUp(size_t level, int32_t c0, int32_t r0, int32_t c1, int32_t r1);
    void updateChunk(int32_t cc, int32_t cr);
    void fineBlock(int32_t level, int32_t c, int32_t r, float& low, float& high) const;
    void releaseChunk(size_t chunk);

    // levels_[k] has blocks of (kBlock << (fineLevels_ + k)) samples; each next: 2 x 2 blocks.
    std::vector<Level> levels_;
    int32_t width_ = 0, height_ = 0;
    int32_t fineLevels_ = 0;             // 0 for a field held whole, kFineLevels for a tiled one
    const SampleTiles* tiles_ = nullptr; // a tiled field's samples
    std::vector<int32_t> chunkSlot_;     // per chunk: its fine blocks in fineLow_/fineHigh_, or -1
    std::vector<float> fineLow_, fineHigh_; // kChunkBlocks per slot
    std::vector<int32_t> freeSlots_;
};

} // namespace hexlod
