// The allocator figures the soak benchmark reads (hexlod_diag_heap): a terrain's samples show
// in the bytes allocated while it lives, and are given back when it is destroyed.
#include "api/hexlod.h"
#include "api/hexlod_diagnostics.h"

#include <gtest/gtest.h>

TEST(HeapAccounting, ATerrainsBytesComeAndGoWithIt) {
    double before[2] = {}, during[2] = {}, after[2] = {};
    ASSERT_EQ(hexlod_diag_heap(before), 0) << hexlod_last_error();
    hexlod_terrain* t = hexlod_terrain_create(1000, 1000, HEXLOD_SAMPLE_F32);
    ASSERT_NE(t, nullptr);
    ASSERT_EQ(hexlod_diag_heap(during), 0);
    EXPECT_GE(during[0] - before[0], 4e6) << "4 MB of samples are allocated";
    EXPECT_GE(during[1], during[0]) << "the allocator holds at least what it handed out";
    hexlod_terrain_destroy(t);
    ASSERT_EQ(hexlod_diag_heap(after), 0);
    EXPECT_LT(after[0] - before[0], 65536.0) << "destroyed, the samples are given back";
    EXPECT_EQ(hexlod_diag_heap(nullptr), HEXLOD_ERROR);
}
