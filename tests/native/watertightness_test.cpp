// Watertightness of the drawn triangles (src/diagnostics/watertightness.h, paper §7): the GPU's
// primitive assembly with restart, and a check that passes the real stream of refined meshes in
// both layouts and embeddings and catches a T-junction, a crack, a hole, an overlap, a flipped
// or degenerate triangle, a free or missing vertex and two pieces apart.
#include "diagnostics/watertightness.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "api/hexlod.h"
#include "api/hexlod_diagnostics.h"
#include "fixture.h"

using namespace hexlod;

namespace {

constexpr uint32_t R = 0xFFFFFFFFu;

// Positions as x, y, z floats a vertex (stride 3), from (x, z) pairs at height 0.
std::vector<float> grid(const std::vector<std::pair<float, float>>& xz) {
    std::vector<float> out;
    for (const auto& [x, z] : xz) out.insert(out.end(), {x, 0.0f, z});
    return out;
}

WatertightStats check(const std::vector<uint32_t>& triangles, const std::vector<float>& positions) {
    return checkWatertight(triangles, positions.data(), positions.size() / 3, 3);
}

// Appends triangle (a, b, c) turned counter-clockwise seen from +y.
void addCcw(std::vector<uint32_t>& out, const std::vector<float>& p, uint32_t a, uint32_t b, uint32_t c) {
    auto x = [&](uint32_t v) { return double(p[3 * v]); };
    auto z = [&](uint32_t v) { return double(p[3 * v + 2]); };
    const double crossY = (z(b) - z(a)) * (x(c) - x(a)) - (x(b) - x(a)) * (z(c) - z(a));
    if (crossY > 0) out.insert(out.end(), {a, b, c});
    else out.insert(out.end(), {a, c, b});
}

bool says(const WatertightStats& s, const char* words) { return s.error && std::string(s.error).find(words) != std::string::npos; }

// A 2 x 1 strip of unit squares seen from above (x east, z south): vertices
//   0 (0,0)  1 (1,0)  2 (2,0)
//   3 (0,1)  4 (1,1)  5 (2,1)
// Counter-clockwise from +y is (a, b, c) with (b.z - a.z)(c.x - a.x) - (b.x - a.x)(c.z - a.z) > 0,
// e.g. (0, 3, 1): down, then up and right.
const std::vector<float> kStrip = grid({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}});
const std::vector<uint32_t> kStripTriangles = {0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5};

} // namespace

TEST(Watertightness, PrimitiveAssemblyRestartsFansAndDropsUnfinishedTriangles) {
    std::vector<uint32_t> out;
    const uint32_t fans[] = {7, 1, 2, 3, 4, R, 8, 5, R, R, 9, 6, 7, R};
    assembleTriangles(fans, std::size(fans), Primitive::TriangleFan, out);
    EXPECT_EQ(out, (std::vector<uint32_t>{7, 1, 2, 7, 2, 3, 7, 3, 4, 9, 6, 7}));
    out.clear();
    const uint32_t list[] = {1, 2, 3, 4, 5, R, 6, 7, 8, R, R, R};
    assembleTriangles(list, std::size(list), Primitive::Triangles, out);
    EXPECT_EQ(out, (std::vector<uint32_t>{1, 2, 3, 6, 7, 8}));
}

TEST(Watertightness, AStripIsOneDiscAndItsDefectsAreNamed) {
    const WatertightStats good = check(kStripTriangles, kStrip);
    ASSERT_EQ(good.error, nullptr) << good.error;
    EXPECT_EQ(good.triangles, 4);
    EXPECT_EQ(good.vertices, 6);
    EXPECT_EQ(good.edges, 9);
    EXPECT_EQ(good.boundaryEdges, 6);
    EXPECT_EQ(good.boundaryLoops, 1);
    EXPECT_EQ(good.euler, 1);

    // A T-junction inside a 3 x 2 grid of squares (vertex r * 4 + c at x = c, z = r): the top
    // middle square is split at the midpoint 12 of its bottom edge 5-6, the square below it is
    // not. Every triangle is fine on its own; the edge 6-5 below and the two halves above form
    // a second boundary loop.
    std::vector<std::pair<float, float>> xz;
    for (int r = 0; r <= 2; ++r)
        for (int c = 0; c <= 3; ++c) xz.emplace_back(float(c), float(r));
    xz.emplace_back(1.5f, 1.0f);
    const std::vector<float> g = grid(xz);
    std::vector<uint32_t> junction;
    for (uint32_t r = 0; r < 2; ++r)
        for (uint32_t c = 0; c < 3; ++c) {
            const uint32_t a = r * 4 + c, b = a + 1, d = a + 4, e = a + 5;
            if (r == 0 && c == 1) {
                for (const auto& [p, q, s] : {std::array<uint32_t, 3>{a, d, 12}, {a, 12, b}, {b, 12, e}}) addCcw(junction, g, p, q, s);
            } else {
                addCcw(junction, g, a, d, b);
                addCcw(junction, g, b, d, e);
            }
        }
    const WatertightStats tj = check(junction, g);
    EXPECT_TRUE(says(tj, "a crack or T-junction: the boundary forms 2 loops, not 1; the shortest (3 edges)")) << (tj.error ? tj.error : "accepted");
    EXPECT_TRUE(says(tj, "(1.000, 1.000)") || says(tj, "(2.000, 1.000)") || says(tj, "(1.500, 1.000)")) << tj.error;
    EXPECT_EQ(tj.boundaryLoops, 2);

    // The same on the outline: the strip's right square split at the midpoint 6 of edge 1-4.
    std::vector<float> t = grid({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 0.5f}});
    std::vector<uint32_t> edgeJunction;
    for (const auto& [p, q, s] : {std::array<uint32_t, 3>{0, 3, 1}, {1, 3, 4}, {1, 6, 2}, {6, 4, 5}, {6, 5, 2}}) addCcw(edgeJunction, t, p, q, s);
    EXPECT_TRUE(says(check(edgeJunction, t), "a crack or T-junction at vertex")) << "a T-junction reaching the outline";

    // A crack: the two squares' shared edge uses different vertices (4 and its copy 6).
    t = grid({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 1}});
    EXPECT_TRUE(says(check({0, 3, 1, 1, 3, 4, 1, 6, 2, 2, 6, 5}, t), "crack or T-junction")) << "a crack";

    // A hole: a square around a missing triangle is a ring.
    const std::vector<float> ring = grid({{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0.9f, 0.9f}, {1.1f, 0.9f}, {1.0f, 1.1f}});
    std::vector<uint32_t> annulus;
    for (const auto& [p, q, s] : {std::array<uint32_t, 3>{0, 4, 1}, {4, 5, 1}, {1, 5, 2}, {5, 6, 2}, {2, 6, 3}, {6, 4, 3}, {3, 4, 0}})
        addCcw(annulus, ring, p, q, s);
    const WatertightStats hole = check(annulus, ring);
    EXPECT_TRUE(says(hole, "2 loops")) << (hole.error ? hole.error : "a hole accepted");

    std::vector<uint32_t> overlap = kStripTriangles;
    overlap.insert(overlap.end(), {0, 3, 1});
    EXPECT_TRUE(says(check(overlap, kStrip), "same direction"));
    std::vector<uint32_t> flipped = kStripTriangles;
    std::swap(flipped[0], flipped[1]);
    EXPECT_TRUE(says(check(flipped, kStrip), "clockwise"));
    EXPECT_TRUE(says(check({0, 1, 2}, kStrip), "degenerate"));
    EXPECT_TRUE(says(check({0, 3, 9}, kStrip), "uses vertex 9 of 6"));
    EXPECT_TRUE(says(check({0, 3}, kStrip), "whole triangles"));
    EXPECT_TRUE(says(check({}, kStrip), "no triangles"));
    std::vector<float> nan = kStrip;
    nan[3 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(says(check(kStripTriangles, nan), "non-finite"));
    const WatertightStats free = checkWatertight(kStripTriangles, kStrip.data(), 6, 3, [](uint32_t v) { return v != 5; });
    EXPECT_TRUE(says(free, "free vertex slot 5"));

    // Two pieces apart: two loops. Two pieces touching at a vertex: a pinch.
    const std::vector<float> two = grid({{0, 0}, {0, 1}, {1, 0}, {5, 0}, {5, 1}, {6, 0}, {2, 1}, {2, -1}});
    EXPECT_TRUE(says(check({0, 1, 2, 3, 4, 5}, two), "2 loops"));
    std::vector<uint32_t> touching;
    addCcw(touching, two, 0, 1, 2);
    addCcw(touching, two, 2, 6, 7);
    EXPECT_TRUE(says(check(touching, two), "pinches"));
}

TEST(Watertightness, TheStreamOfRefinedMeshesIsWatertightInBothLayoutsAndEmbeddings) {
    const auto data = test::readF32(test::kJacksboro);
    ASSERT_FALSE(data.empty());
    for (const int32_t embedding : {HEXLOD_EMBEDDING_EXACT, HEXLOD_EMBEDDING_SHIFTED}) {
        hexlod_terrain* t = hexlod_terrain_create(test::kJacksboro.width, test::kJacksboro.height, HEXLOD_SAMPLE_F32);
        std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
        hexlod_scale scale{};
        scale.spacing_x_m = test::kJacksboro.spacingX;
        scale.spacing_y_m = test::kJacksboro.spacingY;
        ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0);
        ASSERT_EQ(hexlod_terrain_prepare(t, nullptr), 0);
        hexlod_mesh_settings mesh{embedding};
        ASSERT_EQ(hexlod_terrain_reset_mesh(t, &mesh), 0);
        // A low camera over the south edge: every level from the base to the samples is drawn.
        const double w = (test::kJacksboro.width - 1) * double(test::kJacksboro.spacingX);
        const double d = (test::kJacksboro.height - 1) * double(test::kJacksboro.spacingY);
        const hexlod_camera camera{{0.4 * w, 900.0, d - 500.0}, {0.5 * w, 400.0, 0.3 * d}, {0, 0, 0}, 0.5, 1.6, 800.0, 1.0, 1e6};
        for (const int32_t layout : {HEXLOD_LAYOUT_FANS, HEXLOD_LAYOUT_TRIANGLES}) {
            hexlod_settings settings{};
            settings.layout = layout;
            settings.max_operations = 3000;
            ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
            hexlod_frame out{};
            for (int32_t frame = 0; frame < 40 && !out.converged; ++frame) {
                ASSERT_EQ(hexlod_terrain_frame(t, frame == 0 ? &camera : nullptr, HEXLOD_FRAME_ALL, &out), 0);
                double figures[7] = {};
                ASSERT_EQ(hexlod_diag_check_stream(t, figures), 0) << "frame " << frame << ": " << hexlod_last_error();
                EXPECT_EQ(figures[0], out.triangles);
                EXPECT_EQ(figures[4], 1.0);
                EXPECT_EQ(figures[5], 1.0);
                EXPECT_EQ(figures[6], out.index_count);
            }
            EXPECT_GT(out.triangles, 20000.0) << "refined well past the base mesh";
        }
        hexlod_terrain_destroy(t);
    }
}
