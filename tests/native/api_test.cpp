#include "api/hexlod.h"

#include <gtest/gtest.h>

#include <algorithm>
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

    EXPECT_EQ(hexlod_mesh_refine_uniform(t, 1), -1);
    EXPECT_NE(std::string(hexlod_last_error()).find("hexlod_mesh_reset"), std::string::npos);
    EXPECT_EQ(hexlod_mesh_reset(t, 7), -1);
    ASSERT_EQ(hexlod_mesh_reset(t, HEXLOD_EMBEDDING_EXACT), 0);
    const int32_t baseTriangles = hexlod_mesh_triangle_count(t);
    EXPECT_GT(hexlod_mesh_refine_uniform(t, 2), 0);
    EXPECT_EQ(hexlod_mesh_triangle_count(t), 16 * baseTriangles);
    EXPECT_EQ(hexlod_mesh_check(t), 0);
    ASSERT_GE(hexlod_stream_update(t), 0);
    const int32_t fanIndices = hexlod_stream_index_count(t);
    EXPECT_EQ(fanIndices % 9, 0) << "a slot of 9 indices per cell record";
    EXPECT_GE(fanIndices, hexlod_mesh_cell_count(t) * 9);
    const int32_t levelIndices = hexlod_stream_build_level_view(t, 0);
    EXPECT_EQ(hexlod_stream_level_offsets(t)[hexlod_mesh_max_level(t) + 1], levelIndices);
    EXPECT_EQ(hexlod_stream_set_layout(t, 2), -1);
    ASSERT_EQ(hexlod_stream_set_layout(t, HEXLOD_LAYOUT_TRIANGLES), 0);
    EXPECT_EQ(hexlod_stream_index_count(t), fanIndices * 2) << "a slot of 18 indices per cell record";
    EXPECT_EQ(hexlod_lod_set_morph_frames(t, -1), -1);
    EXPECT_EQ(hexlod_lod_set_morph_frames(t, 1001), -1);
    EXPECT_GT(hexlod_mesh_memory_bytes(t), 0.0);
    EXPECT_EQ(hexlod_stream_set_normals(t, 2), -1);
    EXPECT_NE(std::string(hexlod_last_error()).find("on (1) or off (0)"), std::string::npos);
    const double withNormals = hexlod_mesh_memory_bytes(t);
    ASSERT_EQ(hexlod_stream_set_normals(t, 0), 0);
    EXPECT_LT(hexlod_mesh_memory_bytes(t), withNormals) << "off, the stream gives its normal sums back";
    ASSERT_EQ(hexlod_stream_set_normals(t, 1), 0);

    // A new cell size rebuilds the mesh: every position and every cached bound changes.
    ASSERT_EQ(hexlod_lod_set_max_error(t, 20.0), 0);
    ASSERT_EQ(hexlod_lod_update(t) >= 0, true);
    ASSERT_EQ(hexlod_terrain_set_scale(t, 2 * 74.4, 2 * 92.6, 1.0, 0.0, 0, 0.0), 0);
    EXPECT_EQ(hexlod_mesh_triangle_count(t), baseTriangles);
    ASSERT_GE(hexlod_stream_update(t), 0);
    float maxX = 0.0f;
    const auto* vertices = static_cast<const float*>(hexlod_stream_vertices(t));
    for (int32_t v = 0; v < hexlod_stream_vertex_count(t); ++v) maxX = std::max(maxX, vertices[v * 9]);
    EXPECT_GT(maxX, 402 * 74.4f * 1.5f) << "positions use the new spacing";
    while (hexlod_lod_update(t) > 0) {}
    EXPECT_EQ(hexlod_lod_converged(t), 1);
    EXPECT_EQ(hexlod_mesh_check(t), 0);
    hexlod_terrain_destroy(t);
}
