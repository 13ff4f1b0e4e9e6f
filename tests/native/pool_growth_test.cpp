// Pool growth (pool_growth.h): memory is counted per drawn triangle at allocated capacity,
// so a pool that grows one record at a time keeps little unused, and still reallocates
// geometrically (amortised O(1) a record).
#include "mesh/pool_growth.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using namespace hexlod;

TEST(PoolGrowth, APoolGrowingARecordAtATimeKeepsAtMostAThirtySecondAndSixtyFourUnused) {
    std::vector<int32_t> pool;
    size_t reallocations = 0, capacity = 0;
    for (size_t size = 1; size <= 200000; ++size) {
        reserveForPool(pool, size);
        pool.push_back(int32_t(size));
        if (pool.capacity() != capacity) {
            ++reallocations;
            capacity = pool.capacity();
            // Right after a step the room is largest: the record that needed it, a thirty-second
            // of the old capacity and the minimum step.
            ASSERT_LE(capacity, size + (size - 1) / 32 + 64) << "at " << size << " records";
        }
        ASSERT_GE(pool.capacity(), size);
    }
    // Geometric: log(200000 / 64) / log(33 / 32) is about 262 steps, far below one per record.
    EXPECT_LE(reallocations, 300u);
    EXPECT_GE(reallocations, 100u) << "steps of a thirty-second, not doublings";
}

TEST(PoolGrowth, AListGrownByOneLargeEventGivesTheExcessBackOnceDrained) {
    std::vector<int32_t> list(100000, 7);
    list.clear();
    const size_t room = frameListRoom(20000); // an eighth of 20,000 live records
    EXPECT_EQ(room, 2500u);
    trimExcess(list, room);
    EXPECT_EQ(list.capacity(), room);
    const size_t kept = list.capacity();
    list.resize(2 * room); // a steady frame within twice the room: no reallocation back and forth
    list.clear();
    trimExcess(list, room);
    EXPECT_GE(list.capacity(), kept);
    EXPECT_EQ(frameListRoom(100), 256u) << "small meshes keep 256 entries";
}

TEST(PoolGrowth, ACompactedPoolKeepsOneGrowthStepSoTheNextRecordsDoNotReallocate) {
    // 10,000 records, every third one gone: the rest move down in order.
    std::vector<int32_t> pool(10000), map(10000);
    int32_t kept = 0;
    for (int32_t i = 0; i < 10000; ++i) {
        pool[size_t(i)] = i;
        map[size_t(i)] = i % 3 == 0 ? -1 : kept++;
    }
    const size_t room = roomAfterCompaction(size_t(kept));
    EXPECT_EQ(room, size_t(kept) + size_t(kept) / 32 + 64);
    renumberPool(pool, map, size_t(kept), room);
    ASSERT_EQ(pool.size(), size_t(kept));
    EXPECT_EQ(pool.capacity(), room) << "one growth step, not all the old memory and not none";
    for (int32_t i = 0, k = 0; i < 10000; ++i)
        if (i % 3 != 0) ASSERT_EQ(pool[size_t(k++)], i);
    // A shrinking mesh still splits: the records of a few splits fit without a copy.
    const int32_t* storage = pool.data();
    for (int32_t i = 0; i < 200; ++i) {
        reserveForPool(pool, pool.size() + 1);
        pool.push_back(i);
    }
    EXPECT_EQ(pool.data(), storage);
}
