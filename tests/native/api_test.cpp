// The product C ABI (api/hexlod.h) and the diagnostics ABI (api/hexlod_diagnostics.h): one error
// convention, settings where zero means default, one frame call filling one struct.
#include "api/hexlod.h"
#include "api/hexlod_diagnostics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "fixture.h"

namespace {

bool lastErrorMentions(const char* text) { return std::string(hexlod_last_error()).find(text) != std::string::npos; }

hexlod_frame query(hexlod_terrain* t, int32_t extra = 0) {
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_QUERY | extra, &out), 0);
    return out;
}

} // namespace

TEST(Api, NullHandlesAndBadArgumentsReportAClearError) {
    EXPECT_EQ(hexlod_terrain_samples(nullptr), nullptr);
    EXPECT_TRUE(lastErrorMentions("NULL"));
    EXPECT_EQ(hexlod_terrain_create(0, 5, HEXLOD_SAMPLE_U16), nullptr);
    EXPECT_STREQ(hexlod_last_error(), "a height field needs at least 2x2 samples");
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(nullptr, nullptr, 0, &out), HEXLOD_ERROR);
    EXPECT_TRUE(lastErrorMentions("NULL"));
    double h = 0.0;
    EXPECT_EQ(hexlod_terrain_height_at(nullptr, 0.0, 0.0, HEXLOD_SURFACE_DRAWN, &h), HEXLOD_ERROR);
    EXPECT_EQ(hexlod_diag_check_mesh(nullptr), HEXLOD_ERROR);
    hexlod_terrain_destroy(nullptr); // allowed
}

TEST(Api, RoundTripOfARealFieldThroughTheAbi) {
    const auto data = hexlod::test::readF32(hexlod::test::kJacksboro);
    ASSERT_FALSE(data.empty());
    hexlod_terrain* t = hexlod_terrain_create(403, 344, HEXLOD_SAMPLE_F32);
    ASSERT_NE(t, nullptr);
    std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
    hexlod_scale scale{};
    scale.spacing_x_m = 74.0;
    scale.spacing_y_m = 93.0;
    EXPECT_EQ(hexlod_terrain_set_scale(t, &scale), 0);
    hexlod_scale bad = scale;
    bad.spacing_x_m = -1.0;
    EXPECT_EQ(hexlod_terrain_set_scale(t, &bad), HEXLOD_ERROR);
    EXPECT_STREQ(hexlod_last_error(), "sample spacing must be positive");
    EXPECT_EQ(hexlod_terrain_set_scale(t, nullptr), HEXLOD_ERROR);
    hexlod_field_info info{};
    EXPECT_EQ(hexlod_terrain_prepare(t, &info), 0);
    EXPECT_EQ(info.missing, 0.0);
    EXPECT_EQ(info.sample_bytes, 403.0 * 344 * 4);
    EXPECT_NEAR(info.min_height_m, 236.0, 0.5);
    EXPECT_NEAR(info.max_height_m, 1076.0, 0.5);
    double height = 0.0;
    EXPECT_EQ(hexlod_terrain_height_at(t, 74.0 * 3, 93.0 * 2, HEXLOD_SURFACE_FIELD, &height), 1);
    EXPECT_FLOAT_EQ(float(height), data[2 * 403 + 3]);

    hexlod_frame out{};
    EXPECT_EQ(hexlod_diag_refine_uniform(t, 1), HEXLOD_ERROR);
    EXPECT_TRUE(lastErrorMentions("hexlod_terrain_reset_mesh"));
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, 0, &out), HEXLOD_ERROR);
    hexlod_mesh_settings mesh{};
    mesh.embedding = 7;
    EXPECT_EQ(hexlod_terrain_reset_mesh(t, &mesh), HEXLOD_ERROR);
    ASSERT_EQ(hexlod_terrain_reset_mesh(t, nullptr), 0); // zero means default: the exact embedding
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, 0, nullptr), HEXLOD_ERROR);
    const double baseTriangles = query(t).triangles;
    EXPECT_GT(hexlod_diag_refine_uniform(t, 2), 0);
    EXPECT_EQ(query(t).triangles, 16 * baseTriangles);
    EXPECT_EQ(hexlod_diag_check_mesh(t), 0);
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_STREAM, &out), 0);
    const int32_t fanIndices = out.index_count;
    EXPECT_EQ(fanIndices % 9, 0) << "a slot of 9 indices per cell record";
    EXPECT_GE(fanIndices, out.cells * 9);
    EXPECT_GT(out.dirty_index_pairs, 0);
    EXPECT_NE(out.indices_ptr, nullptr);
    EXPECT_EQ(hexlod_terrain_acknowledge(t), 0);
    EXPECT_EQ(query(t).dirty_index_pairs, 0) << "acknowledged ranges are forgotten";
    hexlod_level_view levels{};
    const int32_t levelIndices = hexlod_terrain_level_view(t, 0, &levels);
    EXPECT_EQ(levels.level_offset_count, out.max_level + 2);
    EXPECT_EQ(levels.level_offsets[out.max_level + 1], levelIndices);

    hexlod_settings settings{};
    settings.layout = 2;
    EXPECT_EQ(hexlod_terrain_set_settings(t, &settings), HEXLOD_ERROR);
    settings.layout = HEXLOD_LAYOUT_TRIANGLES;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    EXPECT_EQ(query(t).index_count, fanIndices * 2) << "a slot of 18 indices per cell record";
    settings.morph_frames = -1;
    EXPECT_EQ(hexlod_terrain_set_settings(t, &settings), HEXLOD_ERROR);
    settings.morph_frames = 1001;
    EXPECT_EQ(hexlod_terrain_set_settings(t, &settings), HEXLOD_ERROR);
    settings.morph_frames = 0;
    settings.tau_px = -1.0;
    EXPECT_EQ(hexlod_terrain_set_settings(t, &settings), HEXLOD_ERROR);
    EXPECT_TRUE(lastErrorMentions("tau"));
    settings.tau_px = 0.0;
    const double withNormals = query(t).memory_bytes;
    EXPECT_GT(withNormals, 0.0);
    settings.no_normals = 1;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    EXPECT_LT(query(t).memory_bytes, withNormals) << "off, the stream gives its normal sums back";
    settings.no_normals = 0;

    // A new cell size rebuilds the mesh: every position and every cached bound changes.
    settings.max_error_m = 20.0;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_LOD, &out), 0);
    scale.spacing_x_m = 2 * 74.4;
    scale.spacing_y_m = 2 * 92.6;
    ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0);
    EXPECT_EQ(query(t).triangles, baseTriangles);
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_STREAM, &out), 0);
    float maxX = 0.0f;
    const auto* vertices = static_cast<const float*>(out.vertices_ptr);
    for (int32_t v = 0; v < out.vertex_count; ++v) maxX = std::max(maxX, vertices[v * 5]); // 5 words a vertex (hexlod.h)
    EXPECT_GT(maxX, 402 * 74.4f * 1.5f) << "positions use the new spacing";
    do ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_LOD, &out), 0);
    while (out.operations > 0);
    EXPECT_EQ(out.converged, 1);
    EXPECT_EQ(hexlod_diag_check_mesh(t), 0);
    const hexlod_frame hashed = query(t, HEXLOD_FRAME_HASH | HEXLOD_FRAME_CENSUS);
    EXPECT_NE(uint64_t(hashed.hash_high) << 32 | hashed.hash_low, 0u);
    EXPECT_EQ(hashed.achieved_error_px, -1.0) << "no screen error in max-error mode";
    hexlod_terrain_destroy(t);
}
