// Height bounds for the refinement data of paper §5 / §5.1; see min_max_pyramid.h.
#include "field/min_max_pyramid.h"

#include <algorithm>

namespace hexlod {

void MinMaxPyramid::build(const Heightfield& field) {
    width_ = field.width();
    height_ = field.height();
    levels_.clear();
    // A tiled field's too: its bounds must be the whole field's once its tiles are in.
    block_ = kBlock;
    Level base;
    base.columns = (width_ + block_ - 1) / block_;
    base.rows = (height_ + block_ - 1) / block_;
    base.low.assign(size_t(base.columns) * base.rows, 1e30f);
    base.high.assign(size_t(base.columns) * base.rows, -1e30f);
    if (!field.tiles()) {
        for (int32_t i = 0; i < height_; ++i) {
            const size_t blockRow = size_t(i / kBlock) * size_t(base.columns);
            for (int32_t j = 0; j < width_; ++j) {
                const float h = field.heightAt(j, i);
                const size_t b = blockRow + size_t(j / kBlock);
                base.low[b] = std::min(base.low[b], h);
                base.high[b] = std::max(base.high[b], h);
            }
        }
    }
    levels_.push_back(std::move(base));
    while (levels_.back().columns > 1 || levels_.back().rows > 1) {
        const Level& fine = levels_.back();
        Level coarse;
        coarse.columns = (fine.columns + 1) / 2;
        coarse.rows = (fine.rows + 1) / 2;
        coarse.low.assign(size_t(coarse.columns) * coarse.rows, 1e30f);
        coarse.high.assign(size_t(coarse.columns) * coarse.rows, -1e30f);
        levels_.push_back(std::move(coarse));
        if (!field.tiles()) mergeUp(levels_.size() - 1, 0, 0, levels_.back().columns - 1, levels_.back().rows - 1);
    }
    if (field.tiles()) update(field, {0, 0, width_ - 1, height_ - 1});
}

void MinMaxPyramid::measureBase(const Heightfield& field, int32_t c0, int32_t r0, int32_t c1, int32_t r1) {
    Level& base = levels_[0];
    field.tiles()->blockRanges(block_, c0, r0, c1, r1, size_t(base.columns), base.low.data(), base.high.data());
}

// Level `level`'s blocks [c0, c1] x [r0, r1] from the four blocks under each.
void MinMaxPyramid::mergeUp(size_t level, int32_t c0, int32_t r0, int32_t c1, int32_t r1) {
    const Level& fine = levels_[level - 1];
    Level& coarse = levels_[level];
    for (int32_t r = r0; r <= r1; ++r)
        for (int32_t c = c0; c <= c1; ++c) {
            float low = 1e30f, high = -1e30f;
            for (int32_t fr = 2 * r; fr <= std::min(2 * r + 1, fine.rows - 1); ++fr)
                for (int32_t fc = 2 * c; fc <= std::min(2 * c + 1, fine.columns - 1); ++fc) {
                    low = std::min(low, fine.low[size_t(fr) * fine.columns + fc]);
                    high = std::max(high, fine.high[size_t(fr) * fine.columns + fc]);
                }
            coarse.low[size_t(r) * coarse.columns + c] = low;
            coarse.high[size_t(r) * coarse.columns + c] = high;
        }
}

void MinMaxPyramid::update(const Heightfield& field, const SampleRect& rect) {
    if (!field.tiles() || rect.empty() || levels_.empty()) return;
    int32_t c0 = std::max(0, rect.j0 / block_), r0 = std::max(0, rect.i0 / block_);
    int32_t c1 = std::min(levels_[0].columns - 1, rect.j1 / block_), r1 = std::min(levels_[0].rows - 1, rect.i1 / block_);
    measureBase(field, c0, r0, c1, r1);
    for (size_t level = 1; level < levels_.size(); ++level) {
        c0 /= 2, r0 /= 2, c1 /= 2, r1 /= 2;
        mergeUp(level, c0, r0, c1, r1);
    }
}

void MinMaxPyramid::query(int32_t j0, int32_t i0, int32_t j1, int32_t i1, float& low, float& high) const {
    j0 = std::clamp(j0, 0, width_ - 1), j1 = std::clamp(j1, 0, width_ - 1);
    i0 = std::clamp(i0, 0, height_ - 1), i1 = std::clamp(i1, 0, height_ - 1);
    // The finest level at which the range spans at most 4 blocks per side.
    int32_t blockSize = block_;
    size_t level = 0;
    while (level + 1 < levels_.size() && std::max(j1 / blockSize - j0 / blockSize, i1 / blockSize - i0 / blockSize) >= 4) {
        blockSize *= 2;
        ++level;
    }
    const Level& l = levels_[level];
    low = 1e30f;
    high = -1e30f;
    for (int32_t r = i0 / blockSize; r <= i1 / blockSize; ++r)
        for (int32_t c = j0 / blockSize; c <= j1 / blockSize; ++c) {
            low = std::min(low, l.low[size_t(r) * l.columns + c]);
            high = std::max(high, l.high[size_t(r) * l.columns + c]);
        }
}

size_t MinMaxPyramid::memoryBytes() const {
    size_t bytes = 0;
    for (const Level& l : levels_) bytes += (l.low.capacity() + l.high.capacity()) * sizeof(float);
    return bytes;
}

} // namespace hexlod
