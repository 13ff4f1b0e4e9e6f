// MinMaxPyramid: the lowest and highest height over blocks of samples, and over blocks of
// blocks, built once at load (one pass over the samples). It bounds the heights under a
// large cell without scanning its samples (paper §5.1 scans them; a 16k field's base cells
// would hold hundreds of millions).
//
// A field that arrives by tiles (field/sample_tiles.h) may be far larger than memory, and so
// would be a pyramid over all of it (67 MB at 40000², 420 MB at 100000²). Its levels of blocks
// under a chunk's side are kept only for the chunks whose heights come, somewhere, from the full
// resolution or a level close to it (keepLevel), so they grow with the tiles held, not with the
// field; elsewhere those blocks are measured from the coarser samples when asked (few, since the
// heights there come from an overview). A chunk is kChunk samples a side, or larger for a field
// with more than kMaxChunks of them (a world DEM at 1″: 2048, 194,000 chunks, 3 MB where 256
// made 12 million, 180 MB); the keep level follows, so a block measured on demand still reads
// no more than about 64² samples. The bounds are the same as a whole field's once the tiles
// are in.
#pragma once

#include <cstdint>
#include <vector>

#include "field/heightfield.h"

namespace hexlod {

class MinMaxPyramid {
public:
    static constexpr int32_t kBlock = 16;  // samples per block side at the finest level
    static constexpr int32_t kChunk = 256; // a tiled field's blocks this size and up are kept for all of it...
    static constexpr int64_t kMaxChunks = int64_t(1) << 18; // ...unless there are more chunks than this
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
    // A tiled field's levels under its chunk, per chunk: blocks of 16, 32, ..., chunk / 2 samples.
    static constexpr int32_t kMaxFineLevels = 24;

    void mergeUp(size_t level, int32_t c0, int32_t r0, int32_t c1, int32_t r1);
    // Chunk (cc, cr) after the heights in `rect` changed.
    void updateChunk(int32_t cc, int32_t cr, const SampleRect& rect);
    void fineBlock(int32_t level, int32_t c, int32_t r, float& low, float& high) const;
    void releaseChunk(size_t chunk);

    // levels_[k] has blocks of (kBlock << (fineLevels_ + k)) samples; each next: 2 x 2 blocks.
    std::vector<Level> levels_;
    int32_t width_ = 0, height_ = 0;
    int32_t fineLevels_ = 0;             // 0 for a field held whole; a tiled one: log2(chunk_ / kBlock)
    int32_t chunk_ = kChunk;             // samples a chunk side (a tiled field)
    int32_t chunkSide_ = 0;              // finest blocks across a chunk
    int32_t keepLevel_ = 0;              // a chunk's fine blocks are kept where heights come from this level or finer
    int32_t fineOffset_[kMaxFineLevels] = {}; // where each fine level starts among a chunk's blocks
    int32_t chunkBlocks_ = 0;            // fine blocks a chunk
    const SampleTiles* tiles_ = nullptr; // a tiled field's samples
    std::vector<int32_t> chunkSlot_;     // per chunk: its fine blocks in fineLow_/fineHigh_, or -1
    std::vector<float> fineLow_, fineHigh_; // chunkBlocks_ per slot
    std::vector<int32_t> freeSlots_;
};

} // namespace hexlod
