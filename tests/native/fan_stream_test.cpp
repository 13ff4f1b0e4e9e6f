// The fan stream (paper §7): decoding the fans gives exactly the mesh's triangles, restart
// indices close every fan, levels are contiguous ranges, normals are unit and upward.
#include "fan_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixture.h"
#include "hex_mesh_refine.h"

using namespace hexlod;

namespace {

std::vector<uint32_t> decodeFans(const std::vector<uint32_t>& indices) {
    std::vector<uint32_t> triangles;
    for (size_t start = 0; start < indices.size();) {
        size_t end = start;
        while (end < indices.size() && indices[end] != kRestartIndex) ++end;
        for (size_t k = start + 1; k + 1 < end; ++k) triangles.insert(triangles.end(), {indices[start], indices[k], indices[k + 1]});
        start = end + 1;
    }
    return triangles;
}

// A refined mesh with every kind of cell at several levels: uniform rounds, then local ones.
HexMesh refinedVolcano(const Heightfield& field) {
    HexMesh mesh;
    mesh.reset(field, Embedding::Exact);
    refineUniformly(mesh, 1);
    refineNear(mesh, 300.0, 250.0, 150.0, 3);
    return mesh;
}

} // namespace

TEST(FanStream, DecodedFansAreExactlyTheMeshTriangles) {
    auto field = test::loadFixture(test::kVolcano);
    ASSERT_NE(field, nullptr);
    HexMesh mesh = refinedVolcano(*field);
    ASSERT_EQ(mesh.checkInvariants(), nullptr);
    FanStream stream;
    buildFanStream(mesh, 1.0f, stream);
    std::vector<uint32_t> expected;
    mesh.appendTriangles(expected);
    EXPECT_EQ(decodeFans(stream.indices), expected);
    EXPECT_EQ(int64_t(expected.size() / 3), mesh.triangleCount());
    // Every fan ends with the restart index, and every index is a live vertex.
    ASSERT_FALSE(stream.indices.empty());
    EXPECT_EQ(stream.indices.back(), kRestartIndex);
    int32_t fans = 0;
    for (uint32_t index : stream.indices) {
        if (index == kRestartIndex) {
            ++fans;
            continue;
        }
        ASSERT_LT(int32_t(index), stream.vertexCount);
        ASSERT_TRUE(mesh.isVertexLive(int32_t(index)));
    }
    EXPECT_EQ(fans, mesh.liveCells());
}

TEST(FanStream, LevelRangesHoldTheFansOfOneLevelEach) {
    auto field = test::loadFixture(test::kVolcano);
    HexMesh mesh = refinedVolcano(*field);
    FanStream stream;
    buildFanStream(mesh, 1.0f, stream);
    ASSERT_EQ(stream.levelOffsets.size(), size_t(mesh.maxLevel()) + 2);
    int levelsUsed = 0;
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level) {
        int32_t cells = 0;
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c)) ++cells;
        const auto begin = stream.indices.begin() + stream.levelOffsets[size_t(level)];
        const auto end = stream.indices.begin() + stream.levelOffsets[size_t(level) + 1];
        EXPECT_EQ(std::count(begin, end, kRestartIndex), cells) << "level " << level;
        levelsUsed += cells > 0;
    }
    EXPECT_GE(levelsUsed, 3) << "the test mesh should mix levels";
    EXPECT_EQ(stream.levelOffsets.back(), int32_t(stream.indices.size()));
}

TEST(FanStream, VerticesAreStoredOnceWithUnitUpwardNormals) {
    auto field = test::loadFixture(test::kVolcano);
    HexMesh mesh = refinedVolcano(*field);
    FanStream stream;
    buildFanStream(mesh, 2.0f, stream);
    for (int32_t v = 0; v < stream.vertexCount; ++v) {
        if (!mesh.isVertexLive(v)) continue;
        const float* p = &stream.vertices[size_t(v) * kFloatsPerVertex];
        ASSERT_EQ(p[0], mesh.vertexPosition(v).x);
        ASSERT_EQ(p[1], 2.0f * mesh.vertexPosition(v).y);
        ASSERT_EQ(p[2], mesh.vertexPosition(v).z);
        ASSERT_NEAR(std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5]), 1.0f, 1e-5f);
        ASSERT_GT(p[4], 0.0f);
    }
}

TEST(FanStream, OutlineHasEveryCellEdgeOnceAndOnlyWhenAskedFor) {
    auto field = test::loadFixture(test::kVolcano);
    HexMesh mesh = refinedVolcano(*field);
    FanStream stream;
    buildFanStream(mesh, 1.0f, stream);
    EXPECT_TRUE(stream.outline.empty()) << "no outline unless the wireframe is shown";
    stream.withOutline = true;
    buildFanStream(mesh, 1.0f, stream);
    std::vector<uint64_t> edges;
    for (size_t k = 0; k < stream.outline.size(); k += 2) {
        const uint32_t a = std::min(stream.outline[k], stream.outline[k + 1]), b = std::max(stream.outline[k], stream.outline[k + 1]);
        edges.push_back(uint64_t(a) << 32 | b);
    }
    std::sort(edges.begin(), edges.end());
    EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end()) << "an edge is outlined twice";
    int64_t cellEdges = 0, shared = 0;
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level)
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c))
            for (int32_t slot = 1; slot <= 6; ++slot) {
                if (mesh.cell(c).vertex[slot] == kNone) continue;
                ++cellEdges;
                shared += mesh.cell(c).opposite[slot - 1] != kNone;
            }
    EXPECT_EQ(int64_t(edges.size()), cellEdges - shared / 2);
}
