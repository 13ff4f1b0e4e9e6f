// Height bounds for the refinement data of paper §5 / §5.1; see min_max_pyramid.h.
#include "field/min_max_pyramid.h"

#include <algorithm>

namespace hexlod {

void MinMaxPyramid::build(const Heightfield& field) {
    width_ = field.width();
    height_ = field.height();
    levels_.clear();
    Level base;
    base.columns = (width_ + kBlock - 1) / kBlock;
    base.rows = (height_ + kBlock - 1) / kBlock;
    base.low.assign(size_t(base.columns) * base.rows, 1e30f);
    base.high.assign(size_t(base.columns) * base.rows, -1e30f);
    for (int32_t i = 0; i < height_; ++i) {
        const size_t blockRow = size_t(i / kBlock) * size_t(base.columns);
        for (int32_t j = 0; j < width_; ++j) {
            const float h = field.heightAt(j, i);
            const size_t b = blockRow + size_t(j / kBlock);
            base.low[b] = std::min(base.low[b], h);
            base.high[b] = std::max(base.high[b], h);
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
        for (int32_t r = 0; r < fine.rows; ++r)
            for (int32_t c = 0; c < fine.columns; ++c) {
                const size_t from = size_t(r) * fine.columns + c, to = size_t(r / 2) * coarse.columns + c / 2;
                coarse.low[to] = std::min(coarse.low[to], fine.low[from]);
                coarse.high[to] = std::max(coarse.high[to], fine.high[from]);
            }
        levels_.push_back(std::move(coarse));
    }
}

void MinMaxPyramid::query(int32_t j0, int32_t i0, int32_t j1, int32_t i1, float& low, float& high) const {
    j0 = std::clamp(j0, 0, width_ - 1), j1 = std::clamp(j1, 0, width_ - 1);
    i0 = std::clamp(i0, 0, height_ - 1), i1 = std::clamp(i1, 0, height_ - 1);
    // The finest level at which the range spans at most 4 blocks per side.
    int32_t blockSize = kBlock;
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
