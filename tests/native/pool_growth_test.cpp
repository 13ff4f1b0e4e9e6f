// Pool growth (pool_growth.h): issue 12 counts memory per drawn triangle at allocated capacity,
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
