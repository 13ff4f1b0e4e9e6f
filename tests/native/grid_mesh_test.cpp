#include "grid_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "fixture.h"

using namespace hexlod;

namespace {

// Signed area of a triangle projected on the ground plane, positive when counter-clockwise
// seen from +y (x east, z south).
double groundArea(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c) {
    return 0.5 * ((double(c.x) - a.x) * (double(b.z) - a.z) - (double(b.x) - a.x) * (double(c.z) - a.z));
}

} // namespace

TEST(GridMesh, TrianglesTileTheWholeFieldCounterClockwiseWithoutGaps) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr) << f->name;
        for (int32_t cells : {1, 7, 64, 10000}) {
            GridMesh mesh;
            ASSERT_TRUE(buildGridMesh(*field, cells, 1.0f, mesh));
            double area = 0.0;
            std::map<std::pair<uint32_t, uint32_t>, int> edgeUse;
            for (size_t t = 0; t < mesh.indices.size(); t += 3) {
                const uint32_t* tri = &mesh.indices[t];
                const double a = groundArea(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
                ASSERT_GT(a, 0.0) << "triangle " << t / 3 << " is clockwise or degenerate";
                area += a;
                for (int k = 0; k < 3; ++k) ++edgeUse[{tri[k], tri[(k + 1) % 3]}];
            }
            const double expected = (f->width - 1) * double(f->spacingX) * (f->height - 1) * double(f->spacingY);
            EXPECT_NEAR(area, expected, expected * 1e-6) << f->name << " cells " << cells;
            // Watertight: every directed edge is used once and an interior edge once each way.
            for (const auto& [edge, count] : edgeUse) ASSERT_EQ(count, 1);
        }
    }
}

TEST(GridMesh, FullResolutionVerticesAreTheSamplesAndNormalsAreUnitAndUp) {
    auto field = test::loadFixture(test::kVolcano);
    ASSERT_NE(field, nullptr);
    GridMesh mesh;
    ASSERT_TRUE(buildGridMesh(*field, 1000, 2.0f, mesh));
    ASSERT_EQ(mesh.vertices.size(), size_t(87 * 61));
    for (int32_t i = 0; i < 61; ++i) {
        for (int32_t j = 0; j < 87; ++j) {
            const MeshVertex& v = mesh.vertices[size_t(i) * 87 + j];
            ASSERT_FLOAT_EQ(v.y, 2.0f * field->heightAt(j, i));
            ASSERT_FLOAT_EQ(v.x, j * 10.0f);
            ASSERT_FLOAT_EQ(v.z, i * 10.0f);
            ASSERT_NEAR(std::sqrt(v.nx * v.nx + v.ny * v.ny + v.nz * v.nz), 1.0f, 1e-5f);
            ASSERT_GT(v.ny, 0.0f);
        }
    }
}

TEST(GridMesh, NormalFollowsTheSlopeOfATiltedPlane) {
    auto field = Heightfield::create(5, 4, SampleType::F32, nullptr);
    float* raw = static_cast<float*>(field->samples());
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 5; ++j) raw[i * 5 + j] = 2.0f * j; // rises 2 m per metre eastward
    field->prepare();
    GridMesh mesh;
    ASSERT_TRUE(buildGridMesh(*field, 100, 1.0f, mesh));
    const float len = std::sqrt(5.0f);
    for (const MeshVertex& v : mesh.vertices) {
        EXPECT_NEAR(v.nx, -2.0f / len, 1e-6f);
        EXPECT_NEAR(v.ny, 1.0f / len, 1e-6f);
        EXPECT_NEAR(v.nz, 0.0f, 1e-6f);
    }
}

TEST(GridMesh, RejectsAZeroCellBudget) {
    auto field = test::loadFixture(test::kVolcano);
    GridMesh mesh;
    EXPECT_FALSE(buildGridMesh(*field, 0, 1.0f, mesh));
    EXPECT_TRUE(mesh.vertices.empty());
}
