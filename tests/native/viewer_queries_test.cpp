// The ABI queries the viewer page needs: cell kinds for the HUD, the drawn surface for the
// walk camera, the achieved screen error. Through the product C ABI, on a real DEM.
#include "api/hexlod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "fixture.h"

namespace {

using hexlod::test::kJacksboro;

hexlod_frame query(hexlod_terrain* t, int32_t extra = 0) {
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_QUERY | extra, &out), 0);
    return out;
}

// One LOD update and the stream; returns the update's operations.
int32_t step(hexlod_terrain* t, int32_t steps = HEXLOD_FRAME_LOD | HEXLOD_FRAME_STREAM) {
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, steps, &out), 0);
    return out.operations;
}

double drawnHeightAt(const hexlod_terrain* t, double x, double z) {
    double h = 0.0;
    EXPECT_GE(hexlod_terrain_height_at(t, x, z, HEXLOD_SURFACE_DRAWN, &h), 0);
    return h;
}

hexlod_terrain* jacksboro() {
    const auto data = hexlod::test::readF32(kJacksboro);
    if (data.empty()) return nullptr;
    hexlod_terrain* t = hexlod_terrain_create(kJacksboro.width, kJacksboro.height, HEXLOD_SAMPLE_F32);
    std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
    hexlod_scale scale{};
    scale.spacing_x_m = kJacksboro.spacingX;
    scale.spacing_y_m = kJacksboro.spacingY;
    hexlod_terrain_set_scale(t, &scale);
    hexlod_terrain_prepare(t, nullptr);
    hexlod_terrain_reset_mesh(t, nullptr);
    return t;
}

// A camera low over the field's south edge looking north, 960 x 600 pixels.
void lookNorth(hexlod_terrain* t, double height) {
    const double w = (kJacksboro.width - 1) * double(kJacksboro.spacingX);
    const double d = (kJacksboro.height - 1) * double(kJacksboro.spacingY);
    const hexlod_camera camera{{0.5 * w, height, d + 2000.0}, {0.5 * w, 400.0, 0.3 * d}, {0, 1, 0}, std::tan(0.44), 1.6,
                               600.0, 1.0, 1e6};
    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, &camera, HEXLOD_FRAME_CAMERA, &out), 0);
}

void set(hexlod_terrain* t, double tau, int32_t morphFrames = 0, int32_t maxOperations = 0, double maxError = 0.0) {
    hexlod_settings settings{};
    settings.tau_px = tau;
    settings.morph_frames = morphFrames;
    settings.max_operations = maxOperations;
    settings.max_error_m = maxError;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
}

// Where the stream draws vertex v now (the shader's blend formula, hexlod.h "The fan stream").
// A stream vertex as hexlod.h documents it, in 4-byte words: position x, y, z at 0..2, the
// morph start height at 3, the morph key at 4.
constexpr int32_t kWords = 5, kY = 1, kMorphFromHeight = 3, kMorphKey = 4;

double drawnVertexHeight(const float* vertex, double frame, double frames) {
    const double key = vertex[kMorphKey];
    double w = 1.0;
    if (key != 0.0 && frames > 0.0) {
        const double t = std::clamp((frame - (std::fabs(key) - 1.0)) / frames, 0.0, 1.0);
        w = key > 0.0 ? t : 1.0 - t;
    }
    return vertex[kMorphFromHeight] + (vertex[kY] - vertex[kMorphFromHeight]) * w;
}

} // namespace

TEST(ViewerQueries, CellKindsAddUpToTheLiveCells) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    lookNorth(t, 3000.0);
    set(t, 1.0);
    for (int k = 0; k < 5; ++k) step(t, HEXLOD_FRAME_LOD);
    const hexlod_frame out = query(t, HEXLOD_FRAME_CENSUS);
    const int32_t kinds[3] = {out.full_hexagons, out.semi_hexagons, out.boundary_semi_hexagons};
    ASSERT_EQ(kinds[0] + kinds[1] + kinds[2], out.cells);
    EXPECT_GT(kinds[0], 0);
    EXPECT_GT(kinds[1], 0) << "a refined mesh has semi-hexagons";
    EXPECT_GT(kinds[2], 0) << "the domain boundary has boundary semi-hexagons";
    // Triangles: 6 per full hexagon, 2 per semi-hexagon, 3 per boundary semi-hexagon.
    EXPECT_EQ(6 * kinds[0] + 2 * kinds[1] + 3 * kinds[2], out.triangles);
    hexlod_terrain_destroy(t);
}

TEST(ViewerQueries, DrawnHeightFollowsTheBlendsAndStaysWithinTheErrorOfTheSamples) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    // Mid-refinement with geomorphing: at every drawn vertex the surface is where the blend
    // puts that vertex, not at its final height.
    lookNorth(t, 2500.0);
    set(t, 0.5, 16, 400);
    for (int k = 0; k < 6; ++k) step(t);
    const hexlod_frame out = query(t);
    const float* pool = static_cast<const float*>(out.vertices_ptr);
    const uint32_t* indices = out.indices_ptr;
    const double frame = out.frame;
    int32_t blending = 0, checked = 0;
    for (int32_t k = 0; k < out.index_count && checked < 1500; ++k) {
        if (indices[k] == 0xFFFFFFFFu) continue;
        const float* v = pool + size_t(indices[k]) * kWords;
        const double drawn = drawnHeightAt(t, v[0], v[2]);
        if (std::isnan(drawn)) continue; // a vertex of the lattice past the field's edge
        ++checked;
        if (v[kMorphKey] != 0.0f && std::fabs(v[kY] - drawnVertexHeight(v, frame, 16)) > 1.0) ++blending;
        EXPECT_NEAR(drawn, drawnVertexHeight(v, frame, 16), 1e-2) << "vertex " << indices[k];
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(blending, 0) << "the check ran while vertices were still blending";

    // Converged to a maximum error of 5 m with no blends: the drawn surface is within 5 m of
    // every sample, and outside the field there is no surface.
    set(t, 0.5, 0, 0, 5.0);
    while (step(t, HEXLOD_FRAME_LOD) > 0) {}
    step(t, HEXLOD_FRAME_STREAM);
    const auto data = hexlod::test::readF32(kJacksboro);
    for (int32_t i = 0; i < kJacksboro.height; i += 11)
        for (int32_t j = 0; j < kJacksboro.width; j += 13) {
            const double h = drawnHeightAt(t, j * double(kJacksboro.spacingX), i * double(kJacksboro.spacingY));
            ASSERT_FALSE(std::isnan(h)) << j << ", " << i;
            EXPECT_NEAR(h, data[size_t(i) * kJacksboro.width + j], 5.0 + 1e-3) << j << ", " << i;
        }
    double outside = 0.0;
    EXPECT_EQ(hexlod_terrain_height_at(t, -5000.0, 100.0, HEXLOD_SURFACE_DRAWN, &outside), 0) << "no surface outside the domain";
    EXPECT_TRUE(std::isnan(outside));
    EXPECT_EQ(hexlod_terrain_height_at(nullptr, 0.0, 0.0, HEXLOD_SURFACE_DRAWN, &outside), HEXLOD_ERROR);
    hexlod_terrain_destroy(t);
}

TEST(ViewerQueries, AchievedErrorIsWithinTauOnceConvergedAndGrowsWhenTheCameraComesCloser) {
    hexlod_terrain* t = jacksboro();
    ASSERT_NE(t, nullptr);
    lookNorth(t, 3000.0);
    set(t, 2.0);
    while (step(t, HEXLOD_FRAME_LOD) > 0) {}
    ASSERT_EQ(query(t).converged, 1);
    const double converged = query(t, HEXLOD_FRAME_CENSUS).achieved_error_px;
    EXPECT_GT(converged, 0.5) << "a converged mesh uses most of its tolerance somewhere";
    EXPECT_LE(converged, 2.0);
    // The same mesh seen from much closer: its cells project larger errors than tau.
    lookNorth(t, 900.0);
    EXPECT_GT(query(t, HEXLOD_FRAME_CENSUS).achieved_error_px, 2.0);
    set(t, 2.0, 0, 0, 10.0);
    EXPECT_EQ(query(t, HEXLOD_FRAME_CENSUS).achieved_error_px, -1.0);
    hexlod_terrain_destroy(t);
}
