// Height bounds for the refinement data of paper §5 / §5.1; see min_max_pyramid.h.
#include "field/min_max_pyramid.h"

#include <algorithm>

namespace hexlod {

void MinMaxPyramid::build(const Heightfield& field) {
    width_ = field.width();
    height_ = field.height();
    levels_.clear();
    tiles_ = field.tiles();
    chunkSlot_.clear(), fineLow_.clear(), fineHigh_.clear(), freeSlots_.clear();
    fineLevels_ = 0, chunk_ = kChunk, keepLevel_ = 0, chunkBlocks_ = 0;
    if (tiles_) {
        auto chunks = [&](int64_t side) { return ((width_ + side - 1) / side) * ((height_ + side - 1) / side); };
        while (chunks(chunk_) > kMaxChunks) chunk_ *= 2, ++keepLevel_;
        chunkSide_ = chunk_ / kBlock;
        for (int32_t side = chunkSide_; side > 1; side /= 2) {
            fineOffset_[fineLevels_++] = chunkBlocks_;
            chunkBlocks_ += side * side;
        }
    }
    const int32_t baseBlock = kBlock << fineLevels_;
    Level base;
    base.columns = (width_ + baseBlock - 1) / baseBlock;
    base.rows = (height_ + baseBlock - 1) / baseBlock;
    base.low.assign(size_t(base.columns) * base.rows, 1e30f);
    base.high.assign(size_t(base.columns) * base.rows, -1e30f);
    if (!tiles_) {
        for (int32_t i = 0; i < height_; ++i) {
            const size_t blockRow = size_t(i / kBlock) * size_t(base.columns);
            for (int32_t j = 0; j < width_; ++j) {
                const float h = field.heightAt(j, i);
                const size_t b = blockRow + size_t(j / kBlock);
                base.low[b] = std::min(base.low[b], h);
                base.high[b] = std::max(base.high[b], h);
            }
        }
    } else {
        chunkSlot_.assign(base.low.size(), -1);
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
        if (!tiles_) mergeUp(levels_.size() - 1, 0, 0, levels_.back().columns - 1, levels_.back().rows - 1);
    }
    if (tiles_) update(field, {0, 0, width_ - 1, height_ - 1});
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

void MinMaxPyramid::releaseChunk(size_t chunk) {
    if (chunkSlot_[chunk] < 0) return;
    freeSlots_.push_back(chunkSlot_[chunk]);
    chunkSlot_[chunk] = -1;
}

// Chunk (cc, cr): its fine blocks kept where its heights come from the keep level or finer
// somewhere (the tiles under it are held), dropped otherwise; its block of the base level
// measured. A chunk kept before has only its blocks in `rect` measured again.
void MinMaxPyramid::updateChunk(int32_t cc, int32_t cr, const SampleRect& rect) {
    Level& base = levels_[0];
    const size_t chunk = size_t(cr) * size_t(base.columns) + size_t(cc);
    const int32_t j0 = cc * chunk_, i0 = cr * chunk_;
    const SampleRect whole{j0, i0, std::min(width_, j0 + chunk_) - 1, std::min(height_, i0 + chunk_) - 1};
    if (tiles_->finestLevelIn(whole) > keepLevel_) {
        releaseChunk(chunk);
        tiles_->range(whole, base.low[chunk], base.high[chunk]);
        return;
    }
    const SampleRect part{std::max(whole.j0, rect.j0), std::max(whole.i0, rect.i0), std::min(whole.j1, rect.j1), std::min(whole.i1, rect.i1)};
    int32_t c0 = (part.j0 - j0) / kBlock, r0 = (part.i0 - i0) / kBlock;
    int32_t c1 = (part.j1 - j0) / kBlock, r1 = (part.i1 - i0) / kBlock;
    if (chunkSlot_[chunk] < 0) {
        if (freeSlots_.empty()) {
            freeSlots_.push_back(int32_t(fineLow_.size() / size_t(chunkBlocks_)));
            fineLow_.resize(fineLow_.size() + size_t(chunkBlocks_));
            fineHigh_.resize(fineHigh_.size() + size_t(chunkBlocks_));
        }
        chunkSlot_[chunk] = freeSlots_.back();
        freeSlots_.pop_back();
        c0 = r0 = 0, c1 = r1 = chunkSide_ - 1; // new: every block
    }
    float* low = fineLow_.data() + size_t(chunkSlot_[chunk]) * size_t(chunkBlocks_);
    float* high = fineHigh_.data() + size_t(chunkSlot_[chunk]) * size_t(chunkBlocks_);
    // The finest blocks over the part; blocks past the field's edge stay empty (no query reaches them).
    for (int32_t r = r0; r <= r1; ++r)
        for (int32_t c = c0; c <= c1; ++c) {
            const int32_t bj = j0 + c * kBlock, bi = i0 + r * kBlock;
            float& l = low[r * chunkSide_ + c];
            float& h = high[r * chunkSide_ + c];
            l = 1e30f, h = -1e30f;
            if (bj <= whole.j1 && bi <= whole.i1) tiles_->range({bj, bi, bj + kBlock - 1, bi + kBlock - 1}, l, h);
        }
    // Each fine level from the one below, then the chunk's block of the base level.
    for (int32_t k = 1; k <= fineLevels_; ++k) {
        const int32_t fineSide = chunkSide_ >> (k - 1), side = chunkSide_ >> k;
        c0 /= 2, r0 /= 2, c1 /= 2, r1 /= 2;
        for (int32_t r = r0; r <= r1; ++r)
            for (int32_t c = c0; c <= c1; ++c) {
                float l = 1e30f, h = -1e30f;
                for (int32_t fr = 2 * r; fr <= 2 * r + 1; ++fr)
                    for (int32_t fc = 2 * c; fc <= 2 * c + 1; ++fc) {
                        l = std::min(l, low[fineOffset_[k - 1] + fr * fineSide + fc]);
                        h = std::max(h, high[fineOffset_[k - 1] + fr * fineSide + fc]);
                    }
                float& outLow = k < fineLevels_ ? low[fineOffset_[k] + r * side + c] : base.low[chunk];
                float& outHigh = k < fineLevels_ ? high[fineOffset_[k] + r * side + c] : base.high[chunk];
                outLow = l, outHigh = h;
            }
    }
}

void MinMaxPyramid::update(const Heightfield& field, const SampleRect& rect) {
    if (!field.tiles() || rect.empty() || levels_.empty()) return;
    int32_t c0 = std::max(0, rect.j0 / chunk_), r0 = std::max(0, rect.i0 / chunk_);
    int32_t c1 = std::min(levels_[0].columns - 1, rect.j1 / chunk_), r1 = std::min(levels_[0].rows - 1, rect.i1 / chunk_);
    for (int32_t r = r0; r <= r1; ++r)
        for (int32_t c = c0; c <= c1; ++c) updateChunk(c, r, rect);
    for (size_t level = 1; level < levels_.size(); ++level) {
        c0 /= 2, r0 /= 2, c1 /= 2, r1 /= 2;
        mergeUp(level, c0, r0, c1, r1);
    }
}

// Block (c, r) of fine level `level` (kBlock << level samples a side) of a tiled field.
void MinMaxPyramid::fineBlock(int32_t level, int32_t c, int32_t r, float& low, float& high) const {
    const int32_t perChunk = chunkSide_ >> level, side = kBlock << level;
    const int32_t slot = chunkSlot_[size_t(r / perChunk) * size_t(levels_[0].columns) + size_t(c / perChunk)];
    if (slot < 0) {
        tiles_->range({c * side, r * side, c * side + side - 1, r * side + side - 1}, low, high);
        return;
    }
    const size_t k = size_t(slot) * size_t(chunkBlocks_) + size_t(fineOffset_[level] + (r % perChunk) * perChunk + c % perChunk);
    low = fineLow_[k], high = fineHigh_[k];
}

void MinMaxPyramid::query(int32_t j0, int32_t i0, int32_t j1, int32_t i1, float& low, float& high) const {
    j0 = std::clamp(j0, 0, width_ - 1), j1 = std::clamp(j1, 0, width_ - 1);
    i0 = std::clamp(i0, 0, height_ - 1), i1 = std::clamp(i1, 0, height_ - 1);
    // The finest level at which the range spans at most 4 blocks per side.
    const int32_t levelCount = fineLevels_ + int32_t(levels_.size());
    int32_t blockSize = kBlock;
    int32_t level = 0;
    while (level + 1 < levelCount && std::max(j1 / blockSize - j0 / blockSize, i1 / blockSize - i0 / blockSize) >= 4) {
        blockSize *= 2;
        ++level;
    }
    low = 1e30f;
    high = -1e30f;
    if (level < fineLevels_) {
        for (int32_t r = i0 / blockSize; r <= i1 / blockSize; ++r)
            for (int32_t c = j0 / blockSize; c <= j1 / blockSize; ++c) {
                float l, h;
                fineBlock(level, c, r, l, h);
                low = std::min(low, l), high = std::max(high, h);
            }
        return;
    }
    const Level& l = levels_[size_t(level - fineLevels_)];
    for (int32_t r = i0 / blockSize; r <= i1 / blockSize; ++r)
        for (int32_t c = j0 / blockSize; c <= j1 / blockSize; ++c) {
            low = std::min(low, l.low[size_t(r) * l.columns + c]);
            high = std::max(high, l.high[size_t(r) * l.columns + c]);
        }
}

size_t MinMaxPyramid::memoryBytes() const {
    size_t bytes = (chunkSlot_.capacity() + freeSlots_.capacity()) * sizeof(int32_t) +
                   (fineLow_.capacity() + fineHigh_.capacity()) * sizeof(float);
    for (const Level& l : levels_) bytes += (l.low.capacity() + l.high.capacity()) * sizeof(float);
    return bytes;
}

} // namespace hexlod
