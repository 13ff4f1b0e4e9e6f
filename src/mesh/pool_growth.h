// Pool storage of paper §4.3 (cell and vertex records in flat arrays).
// Growth of the arrays that hold one element per cell or vertex record. Issue 12 counts memory
// per drawn triangle at allocated capacity: std::vector doubles, so up to half of a pool could
// sit unused. Growing by an eighth keeps the unused share under about 12 %, with reallocations
// still geometric (amortised O(1) per element), so no operation allocates on average.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace hexlod {

/// Makes room for `size` elements in `pool`, growing its capacity by at least an eighth.
template <typename T>
void reserveForPool(std::vector<T>& pool, size_t size) {
    if (size <= pool.capacity()) return;
    constexpr size_t kMinimumGrowth = 1024;
    pool.reserve(std::max(size, pool.capacity() + pool.capacity() / 8 + kMinimumGrowth));
}

} // namespace hexlod
