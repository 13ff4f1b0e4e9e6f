// Pool storage of paper §4.3 (cell and vertex records in flat arrays).
// Growth of the arrays that hold one element per cell or vertex record. Memory is counted
// per drawn triangle at allocated capacity: std::vector doubles, so up to half of a pool could
// sit unused. Growing by a thirty-second keeps the unused share under about 3 %, with
// reallocations still geometric (amortised O(1) per element: each element is moved 32 times on
// average over the pool's growth, a memcpy), so no operation allocates on average. A sixteenth
// left the Grand Canyon's largest figure at 40.5 B per triangle, past the goal of 40; the
// compaction (HexMesh::wantsCompaction) stays at a sixteenth, since each one rewrites and
// uploads the whole stream. The minimum step (64 records) only keeps a small pool from
// reallocating on every few records.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace hexlod {

/// One growth step of a pool of `records`: a thirty-second more, and at least 64 records, which
/// keeps a small pool from reallocating every few records.
inline size_t grownByOneStep(size_t records) { return records + records / 32 + 64; }

/// Makes room for `size` elements in `pool`, growing its capacity by at least one step.
template <typename T>
void reserveForPool(std::vector<T>& pool, size_t size) {
    if (size <= pool.capacity()) return;
    pool.reserve(std::max(size, grownByOneStep(pool.capacity())));
}

/// The room a pool of `size` records keeps after a compaction: one growth step. A shrinking
/// mesh still splits where the camera goes; with no room left, the first split after each
/// compaction copied every pool (and faulted in fresh pages for it).
inline size_t roomAfterCompaction(size_t size) { return grownByOneStep(size); }

/// Makes room for `size` elements in an array that keeps one element per record of a pool
/// (the refiner's caches, the stream's slots): as much room as the pool has, so the two grow
/// together and the array adds no unused share of its own.
template <typename T>
void reserveLikePool(std::vector<T>& perRecord, size_t size, size_t poolCapacity) {
    if (size <= perRecord.capacity()) return;
    perRecord.reserve(std::max(size, poolCapacity));
}

/// Empties a pool and gives its memory back (clear() keeps the capacity): a new mesh, perhaps of
/// a much smaller field, starts from nothing rather than from the last mesh's peak.
template <typename T>
void releasePool(std::vector<T>& pool) {
    std::vector<T>().swap(pool);
}

/// Moves record i of a per-record array (`perRecord` elements each) to map[i] (negative: the
/// record is gone) and keeps `size` records in room for `room` (roomAfterCompaction), giving
/// the rest of the memory back. The map is increasing on the records it keeps
/// (HexMesh::compact), so the moves go downwards and can be made in place.
template <typename T>
void renumberPool(std::vector<T>& pool, const std::vector<int32_t>& map, size_t size, size_t room, size_t perRecord = 1) {
    const size_t n = std::min(pool.size() / perRecord, map.size());
    for (size_t i = 0; i < n; ++i)
        if (map[i] >= 0) std::copy_n(pool.begin() + ptrdiff_t(i * perRecord), perRecord, pool.begin() + ptrdiff_t(size_t(map[i]) * perRecord));
    std::vector<T> kept;
    kept.reserve(std::max(room, size) * perRecord);
    kept.assign(pool.begin(), pool.begin() + ptrdiff_t(std::min(pool.size(), size * perRecord)));
    kept.resize(size * perRecord);
    pool.swap(kept);
}

/// What a frame's logs and work lists keep between frames: room for changes to an eighth of the
/// live records (at least 256). See trimExcess.
inline size_t frameListRoom(size_t liveRecords) { return std::max<size_t>(256, liveRecords / 8); }

/// A log or work list that one large event (a new mesh refined in one go, a camera that jumped)
/// grew far past what frames use gives the excess back once it is drained: past twice `room`
/// it is cut to `room`, contents kept. The factor two is hysteresis, so frames of a steady
/// flight never reallocate; only the frame after such an event does, once (a shrinking mesh
/// also shrinks the room now and then: 50 trims over the 300 frames of the Grand Canyon at
/// 50 m a frame, 47 with the factor four and 1024 that a small mesh's lists kept before).
template <typename T>
void trimExcess(std::vector<T>& list, size_t room) {
    if (list.capacity() <= 2 * room || list.size() > room) return;
    std::vector<T> trimmed;
    trimmed.reserve(room);
    trimmed.assign(list.begin(), list.end());
    list.swap(trimmed);
}

} // namespace hexlod
