// MinMaxPyramid: the lowest and highest height over blocks of samples, and over blocks of
// blocks, built once at load (one pass over the samples). It bounds the heights under a
// large cell without scanning its samples (paper §5.1 scans them; a 16k field's base cells
// would hold hundreds of millions).
#pragma once

#include <cstdint>
#include <vector>

#include "field/heightfield.h"

namespace hexlod {

class MinMaxPyramid {
public:
    static constexpr int32_t kBlock = 16; // samples per block side at the finest level
    /// The block side in use.
    int32_t block() const { return block_; }

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
    void measureBase(const Heightfield& field, int32_t c0, int32_t r0, int32_t c1, int32_t r1);
    void mergeUp(size_t level, int32_t c0, int32_t r0, int32_t c1, int32_t r1);
    std::vector<Level> levels_; // levels_[0]: block_ x block_ samples per block; each next: 2 x 2 blocks
    int32_t width_ = 0, height_ = 0;
    int32_t block_ = kBlock;
};

} // namespace hexlod
