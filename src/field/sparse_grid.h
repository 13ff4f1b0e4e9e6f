// SparseGrid: a two-dimensional array of any size that holds memory only where it was written,
// for what a field that arrives by tiles (field/sample_tiles.h) keeps per tile. A world DEM at
// 1″ has three million full-resolution tiles of 512² samples; a dense array of a few bytes a
// tile, per level and per user, came to a hundred MB while the view holds a few hundred tiles.
//
// Elements live in pages of kPage x kPage, a page allocated at the first write into it and kept
// until reset(); an element of a page never written reads as the fill value. Memory grows with
// the area written to, not with the grid's size.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hexlod {

template <typename T>
class SparseGrid {
public:
    static constexpr int32_t kPageShift = 5;
    static constexpr int32_t kPage = 1 << kPageShift; // elements a page side

    /// A grid of columns x rows elements (each >= 0), all `fill`; gives every page back.
    void reset(int32_t columns, int32_t rows, const T& fill) {
        columns_ = columns, rows_ = rows, fill_ = fill;
        pagesAcross_ = (columns + kPage - 1) >> kPageShift;
        const int32_t pagesDown = (rows + kPage - 1) >> kPageShift;
        std::vector<int32_t>(size_t(pagesAcross_) * size_t(pagesDown), -1).swap(page_);
        std::vector<T>().swap(elements_);
    }

    int32_t columns() const { return columns_; }
    int32_t rows() const { return rows_; }

    /// Element (c, r), inside the grid; the fill value where nothing was written.
    const T& get(int32_t c, int32_t r) const {
        const int32_t p = page_[pageOf(c, r)];
        return p < 0 ? fill_ : elements_[size_t(p) + offsetIn(c, r)];
    }
    /// Element (c, r), inside the grid, to write: its page is allocated (filled) if it was not.
    T& at(int32_t c, int32_t r) {
        int32_t& p = page_[pageOf(c, r)];
        if (p < 0) {
            p = int32_t(elements_.size());
            elements_.resize(elements_.size() + size_t(kPage) * kPage, fill_);
        }
        return elements_[size_t(p) + offsetIn(c, r)];
    }
    /// Sets every element written so far to `value` (pages stay allocated).
    void fillWritten(const T& value) { std::fill(elements_.begin(), elements_.end(), value); }

    size_t memoryBytes() const { return page_.capacity() * sizeof(int32_t) + elements_.capacity() * sizeof(T); }

private:
    size_t pageOf(int32_t c, int32_t r) const { return size_t(r >> kPageShift) * size_t(pagesAcross_) + size_t(c >> kPageShift); }
    static size_t offsetIn(int32_t c, int32_t r) { return size_t(r & (kPage - 1)) << kPageShift | size_t(c & (kPage - 1)); }

    int32_t columns_ = 0, rows_ = 0, pagesAcross_ = 0;
    T fill_{};
    std::vector<int32_t> page_; // per page: the index of its first element in elements_, or -1
    std::vector<T> elements_;
};

} // namespace hexlod
