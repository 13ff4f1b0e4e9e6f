#include "hexlod.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "fixture.h"

TEST(Api, NullHandlesAndBadArgumentsReportAClearError) {
    EXPECT_EQ(hexlod_terrain_samples(nullptr), nullptr);
    EXPECT_NE(std::string(hexlod_last_error()).find("NULL"), std::string::npos);
    EXPECT_EQ(hexlod_terrain_create(0, 5, HEXLOD_SAMPLE_U16), nullptr);
    EXPECT_STREQ(hexlod_last_error(), "a height field needs at least 2x2 samples");
    hexlod_terrain_destroy(nullptr); // allowed
}

TEST(Api, RoundTripOfARealFieldThroughTheAbi) {
    const auto data = hexlod::test::readF32(hexlod::test::kJacksboro);
    ASSERT_FALSE(data.empty());
    hexlod_terrain* t = hexlod_terrain_create(403, 344, HEXLOD_SAMPLE_F32);
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(hexlod_terrain_sample_bytes(t), 403.0 * 344 * 4);
    std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
    EXPECT_EQ(hexlod_terrain_set_scale(t, 74.0, 93.0, 1.0, 0.0, 0, 0.0), 0);
    EXPECT_EQ(hexlod_terrain_set_scale(t, -1.0, 93.0, 1.0, 0.0, 0, 0.0), -1);
    EXPECT_EQ(hexlod_terrain_prepare(t), 0.0);
    EXPECT_NEAR(hexlod_terrain_min_height(t), 236.0, 0.5);
    EXPECT_NEAR(hexlod_terrain_max_height(t), 1076.0, 0.5);
    EXPECT_FLOAT_EQ(float(hexlod_terrain_height_at(t, 74.0 * 3, 93.0 * 2)), data[2 * 403 + 3]);

    const int32_t vertices = hexlod_grid_mesh_build(t, 50, 1.0f);
    ASSERT_GT(vertices, 0);
    EXPECT_EQ(vertices, hexlod_grid_mesh_vertex_count(t));
    EXPECT_EQ(hexlod_grid_mesh_index_count(t) % 3, 0);
    EXPECT_NE(hexlod_grid_mesh_vertices(t), nullptr);
    EXPECT_EQ(hexlod_grid_mesh_build(t, 0, 1.0f), -1);
    hexlod_terrain_destroy(t);
}
