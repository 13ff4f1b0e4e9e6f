// The ABI queries the viewer page needs: cell kinds for the HUD, the drawn surface for the
// walk camera, the achieved screen error. Through the C ABI, on a real DEM.
#include "api/hexlod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "fixture.h"

namespace {

using hexlod::test::kJacksboro;

hexlod_terrain* jacksboro() {
    const auto data = hexlod::test::readF32(kJacksboro);
    if (data.empty()) return nullptr;
    hexlod_terrain* t = hexlod_terrain_create(kJacksboro.width, kJacksboro.height, HEXLOD_SAMPLE_F32);
    std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
    hexlod_terrain_set_scale(t, kJacksboro.spacingX, kJacksboro.spacingY, 1.0, 0.0, 0, 0.0);
    hexlod_terrain_prepare(t);
    hexlod_mesh_reset(t, HEXLOD_EMBEDDING_EXACT);
    return t;
}

// A camera low over the field's south edge looking north, 960 x 600 pixels.
void lookNorth(hexlod_terrain* t, double height) {
    const double w = (kJacksboro.width - 1) * double(kJacksboro.spacingX);
    const double d = (kJacksboro.height - 1) * double(kJacksboro.spacingY);
    ASSERT_EQ(hexlod_lod_set_camera(t, 0.5 * w, height, d + 2000.0, 0.5 * w, 400.0, 0.3 * d, 0, 1, 0, std::tan(0.44), 1.6,
                                    600.0, 1.0, 1e6),
              0);
}

// Where the stream draws vertex v now (the shader's blend formula, hexlod.h "The fan stream").
double drawnVertexHeight(const float* vertex, double frame, double frames) {
    const double key = vertex[8];
    double w = 1.0;
    if (key != 0.0 && frames > 0.0) {
        const double t = std::clamp((frame - (std::fabs(key) - 1.0)) / frames, 0.0, 1.0);
        w = key > 0.0 ? t : 1.0 - t;
    }
    return vertex[6] + (vertex[1] - vertex[6]) * w;
}

} // namespace

TEST(ViewerQueries, CellKindsAddUpToTheLiveCells) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    int32_t kinds[3];
    EXPECT_EQ(hexlod_mesh_cell_kinds(t, nullptr), -1);
    lookNorth(t, 3000.0);
    hexlod_lod_set_tolerance(t, 1.0);
    for (int k = 0; k < 5; ++k) hexlod_lod_update(t);
    ASSERT_EQ(hexlod_mesh_cell_kinds(t, kinds), hexlod_mesh_cell_count(t));
    EXPECT_GT(kinds[0], 0);
    EXPECT_GT(kinds[1], 0) << "a refined mesh has semi-hexagons";
    EXPECT_GT(kinds[2], 0) << "the domain boundary has boundary semi-hexagons";
    // Triangles: 6 per full hexagon, 2 per semi-hexagon, 3 per boundary semi-hexagon.
    EXPECT_EQ(6 * kinds[0] + 2 * kinds[1] + 3 * kinds[2], hexlod_mesh_triangle_count(t));
    hexlod_terrain_destroy(t);
}

TEST(ViewerQueries, DrawnHeightFollowsTheBlendsAndStaysWithinTheErrorOfTheSamples) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    // Mid-refinement with geomorphing: at every drawn vertex the surface is where the blend
    // puts that vertex, not at its final height.
    lookNorth(t, 2500.0);
    hexlod_lod_set_tolerance(t, 0.5);
    hexlod_lod_set_morph_frames(t, 16);
    hexlod_lod_set_budget(t, 0.0, 400);
    for (int k = 0; k < 6; ++k) {
        hexlod_lod_update(t);
        hexlod_stream_update(t);
    }
    const float* pool = static_cast<const float*>(hexlod_stream_vertices(t));
    const uint32_t* indices = hexlod_stream_indices(t);
    const double frame = hexlod_lod_frame(t);
    int32_t blending = 0, checked = 0;
    for (int32_t k = 0; k < hexlod_stream_index_count(t) && checked < 1500; ++k) {
        if (indices[k] == 0xFFFFFFFFu) continue;
        const float* v = pool + size_t(indices[k]) * 9;
        const double drawn = hexlod_stream_drawn_height_at(t, v[0], v[2]);
        if (std::isnan(drawn)) continue; // a vertex of the lattice past the field's edge
        ++checked;
        if (v[8] != 0.0f && std::fabs(v[1] - drawnVertexHeight(v, frame, 16)) > 1.0) ++blending;
        EXPECT_NEAR(drawn, drawnVertexHeight(v, frame, 16), 1e-2) << "vertex " << indices[k];
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(blending, 0) << "the check ran while vertices were still blending";

    // Converged to a maximum error of 5 m with no blends: the drawn surface is within 5 m of
    // every sample, and outside the field there is no surface.
    hexlod_lod_set_morph_frames(t, 0);
    hexlod_lod_set_budget(t, 0.0, 0);
    hexlod_lod_set_max_error(t, 5.0);
    while (hexlod_lod_update(t) > 0) {}
    hexlod_stream_update(t);
    const auto data = hexlod::test::readF32(kJacksboro);
    for (int32_t i = 0; i < kJacksboro.height; i += 11)
        for (int32_t j = 0; j < kJacksboro.width; j += 13) {
            const double h = hexlod_stream_drawn_height_at(t, j * double(kJacksboro.spacingX), i * double(kJacksboro.spacingY));
            ASSERT_FALSE(std::isnan(h)) << j << ", " << i;
            EXPECT_NEAR(h, data[size_t(i) * kJacksboro.width + j], 5.0 + 1e-3) << j << ", " << i;
        }
    EXPECT_TRUE(std::isnan(hexlod_stream_drawn_height_at(t, -5000.0, 100.0)));
    EXPECT_TRUE(std::isnan(hexlod_stream_drawn_height_at(nullptr, 0.0, 0.0)));
    hexlod_terrain_destroy(t);
}

TEST(ViewerQueries, AchievedErrorIsWithinTauOnceConvergedAndGrowsWhenTheCameraComesCloser) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    lookNorth(t, 3000.0);
    hexlod_lod_set_tolerance(t, 2.0);
    while (hexlod_lod_update(t) > 0) {}
    ASSERT_EQ(hexlod_lod_converged(t), 1);
    const double converged = hexlod_lod_achieved_error_px(t);
    EXPECT_GT(converged, 0.5) << "a converged mesh uses most of its tolerance somewhere";
    EXPECT_LE(converged, 2.0);
    // The same mesh seen from much closer: its cells project larger errors than tau.
    lookNorth(t, 900.0);
    EXPECT_GT(hexlod_lod_achieved_error_px(t), 2.0);
    hexlod_lod_set_max_error(t, 10.0);
    EXPECT_EQ(hexlod_lod_achieved_error_px(t), -1.0);
    hexlod_terrain_destroy(t);
}
