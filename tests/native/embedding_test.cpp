// The two lattice embeddings (§4.7), measured against the original samples at full
// refinement, and the memory the mesh structures take per triangle (§8.1).
#include "mesh/embedding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "diagnostics/error_evaluator.h"
#include "stream/fan_stream.h"
#include "fixture.h"
#include "mesh/hex_mesh_refine.h"

using namespace hexlod;

namespace {

struct Measured {
    ErrorStats stats;
    int64_t triangles = 0;
    size_t meshBytes = 0, vertexPoolBytes = 0, streamBytes = 0;
};

Measured measureFullRefinement(const Heightfield& field, Embedding embedding) {
    HexMesh mesh;
    mesh.reset(field, embedding);
    refineUniformly(mesh, mesh.maxLevel() / 2);
    std::vector<uint32_t> triangles;
    mesh.appendTriangles(triangles);
    Measured m;
    m.stats = evaluateMeshError(field, mesh.positionData(), size_t(mesh.vertexCapacity()), kStreamVertexWords,
                                triangles.data(), triangles.size());
    m.triangles = mesh.triangleCount();
    m.meshBytes = mesh.memoryBytes();
    m.vertexPoolBytes = mesh.vertexPoolBytes();
    FanStream stream;
    stream.attach(mesh);
    m.streamBytes = stream.memoryBytes();
    return m;
}

// The shifted embedding's error at full refinement, from the samples alone: an odd-row sample
// lies halfway between two vertices that each average two samples, |h(j-1) - 2h(j) + h(j+1)|/4
// (columns clamped at the edges); even rows are exact.
double shiftedFullRefinementError(const Heightfield& field) {
    double worst = 0.0;
    for (int32_t i = 1; i < field.height(); i += 2)
        for (int32_t j = 0; j < field.width(); ++j) {
            const double d2 = double(field.heightClamped(j - 1, i)) - 2.0 * field.heightAt(j, i) + field.heightClamped(j + 1, i);
            worst = std::max(worst, std::abs(d2) / 4.0);
        }
    return worst;
}

} // namespace

TEST(Embedding, CoarseVerticesSitOnRealSamplesInBothEmbeddings) {
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr);
    for (Embedding embedding : {Embedding::Shifted, Embedding::Exact}) {
        for (int32_t r = 0; r < 64; r += 2) {
            for (int32_t q = -40; q < 40; q += 2) {
                const LatticePoint p{q, r};
                const int32_t j = sampleColumn(p);
                if (j < 0 || j >= field->width()) continue;
                const glm::vec3 v = embedLatticePoint(*field, embedding, p);
                ASSERT_EQ(v.y, field->heightAt(j, r));
                ASSERT_EQ(v.x, float(double(j) * field->scale().spacingX));
            }
        }
    }
}

// The mesh stores no lattice points: it recovers them from the float positions the
// embedding made of them, which must be exact for every point a mesh can have (tiled fields up
// to kMaxTiledFieldSide a side, plus the lattice's overhang of up to a quarter side and a few
// samples), at any accepted spacing.
TEST(Embedding, EveryLatticePointComesBackFromItsPosition) {
    auto field = Heightfield::create(9, 9, SampleType::F32, nullptr);
    ASSERT_TRUE(field);
    field->prepare();
    const double spacings[] = {kMinSpacing, 1e-3, 0.5, 1.0, 30.87, 92.66, 1234.5678, 1e6, kMaxSpacing};
    const int32_t reach = kMaxTiledFieldSide + kMaxTiledFieldSide / 4 + 5; // columns and rows
    for (Embedding embedding : {Embedding::Shifted, Embedding::Exact}) {
        for (double sx : spacings) {
            for (double sy : {spacings[0], spacings[3], spacings[5], spacings[8]}) {
                HeightfieldScale scale;
                scale.spacingX = sx, scale.spacingY = sy;
                ASSERT_EQ(field->setScale(scale), nullptr);
                HexMesh mesh;
                ASSERT_EQ(mesh.reset(*field, embedding), nullptr);
                int32_t checked = 0;
                // A point of sample column j and row r.
                auto at = [](int32_t j, int32_t r) { return LatticePoint{j - floorDiv2(r), r}; };
                for (int32_t r = -reach; r <= reach; r += 997 * 16) {
                    for (int32_t j = -reach; j <= reach; j += 1009 * 16) {
                        for (LatticePoint p : {at(j, r), at(j + 1, r + 1), at(-j, reach), at(reach, -r), at(-reach, r), at(j, -reach)}) {
                            const LatticePoint back = mesh.latticeAt(embedLatticePoint(*field, embedding, p));
                            ASSERT_EQ(back, p) << "spacing " << sx << " x " << sy << " at (" << p.q << ", " << p.r << ")";
                            ++checked;
                        }
                    }
                }
                EXPECT_GT(checked, 100000);
            }
        }
    }
    // Outside the accepted range the field refuses the spacing, so no mesh is built with it.
    HeightfieldScale tiny;
    tiny.spacingX = kMinSpacing / 2;
    EXPECT_NE(field->setScale(tiny), nullptr);
    HeightfieldScale huge;
    huge.spacingY = kMaxSpacing * 2;
    EXPECT_NE(field->setScale(huge), nullptr);
}

TEST(Embedding, ExactIsErrorFreeAtFullRefinementAndShiftedSmoothsOddRows) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro, &test::kGrandCanyon}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr);
        const Measured exact = measureFullRefinement(*field, Embedding::Exact);
        const Measured shifted = measureFullRefinement(*field, Embedding::Shifted);
        std::printf("embedding error at full refinement, %s (%dx%d): shifted max %.3f m p99 %.3f m; exact max %.3f m p99 %.3f m\n",
                    f->name, f->width, f->height, shifted.stats.maxError, shifted.stats.p99Error,
                    exact.stats.maxError, exact.stats.p99Error);
        for (const Measured* m : {&exact, &shifted}) {
            ASSERT_EQ(m->stats.error, nullptr);
            EXPECT_EQ(m->stats.uncovered, 0) << f->name << ": the mesh must cover the whole field";
            EXPECT_EQ(m->stats.evaluated, int64_t(f->width) * f->height);
        }
        EXPECT_EQ(exact.stats.maxError, 0.0) << f->name;
        EXPECT_NEAR(shifted.stats.maxError, shiftedFullRefinementError(*field), 1e-3) << f->name;
        EXPECT_GT(shifted.stats.maxError, 1.0) << f->name << ": real terrain has curvature";
    }
}

TEST(Embedding, MeshStructuresTakeFewBytesPerTriangle) {
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr);
    const Measured m = measureFullRefinement(*field, Embedding::Exact);
    const double topology = double(m.meshBytes - m.vertexPoolBytes) / double(m.triangles);
    const double drawing = double(m.meshBytes + m.streamBytes) / double(m.triangles);
    std::printf("mesh at full refinement of grandcanyon_512: %lld triangles; topology (records %zu B each, lattice "
                "points, parents, lists) %.1f B/triangle; with the vertex pool and the fan stream %.1f B/triangle "
                "(paper §8.1: about 15 B per triangle for records, 64 B in all)\n",
                (long long)m.triangles, sizeof(Hexagon), topology, drawing);
    EXPECT_GT(m.triangles, int64_t(2) * 511 * 511);
    EXPECT_LT(topology, 40.0);
    EXPECT_LT(drawing, 100.0);
}
