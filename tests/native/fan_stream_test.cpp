// The fan stream (paper §7): decoding the slots gives exactly the mesh's triangles, restart
// indices close every fan, nothing exceeds capacity, incremental updates equal a rewrite bit
// for bit, and the dirty ranges carry every change to a renderer's copy.
#include "stream/fan_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "fixture.h"
#include "mesh/hex_mesh_refine.h"

using namespace hexlod;

namespace {

using Triangle = std::array<uint32_t, 3>;

// Decodes one slot per cell into triangles, checking the slot's shape on the way.
std::vector<Triangle> decode(const FanStream& stream) {
    std::vector<Triangle> out;
    const std::vector<uint32_t>& idx = stream.indices();
    const int32_t size = stream.slotSize();
    for (size_t first = 0; first < idx.size(); first += size_t(size)) {
        const uint32_t* slot = idx.data() + first;
        if (stream.layout() == IndexLayout::Fans) {
            int32_t n = 0;
            while (n < size && slot[n] != kRestartIndex) ++n;
            EXPECT_LT(n, size) << "a fan slot must end with the restart index";
            for (int32_t k = n; k < size; ++k) EXPECT_EQ(slot[k], kRestartIndex) << "only restarts after the fan";
            for (int32_t k = 1; k + 1 < n; ++k) out.push_back({slot[0], slot[k], slot[k + 1]});
        } else {
            for (int32_t k = 0; k < size; k += 3) {
                if (slot[k] == kRestartIndex) {
                    EXPECT_TRUE(slot[k + 1] == kRestartIndex && slot[k + 2] == kRestartIndex) << "padding is whole triangles";
                    continue;
                }
                out.push_back({slot[k], slot[k + 1], slot[k + 2]});
            }
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<Triangle> meshTriangles(const HexMesh& mesh) {
    std::vector<uint32_t> flat;
    mesh.appendTriangles(flat);
    std::vector<Triangle> out;
    for (size_t t = 0; t < flat.size(); t += 3) out.push_back({flat[t], flat[t + 1], flat[t + 2]});
    std::sort(out.begin(), out.end());
    return out;
}

// A refined mesh with every kind of cell at several levels: uniform rounds, then local ones.
void refineVolcano(HexMesh& mesh, const Heightfield& field) {
    mesh.reset(field, Embedding::Exact);
    refineUniformly(mesh, 1);
    refineNear(mesh, 300.0, 250.0, 150.0, 3);
}

// The refined volcano with its stream, built in place (the stream points at the mesh).
struct VolcanoStream {
    std::unique_ptr<Heightfield> field = test::loadFixture(test::kVolcano);
    HexMesh mesh;
    FanStream stream;
    VolcanoStream() {
        refineVolcano(mesh, *field);
        stream.attach(mesh);
    }
};

// Random splits and merges, as a moving camera would cause.
void randomOperations(HexMesh& mesh, std::mt19937& random, int32_t count) {
    for (int32_t i = 0; i < count; ++i) {
        const int32_t c = int32_t(random() % uint32_t(mesh.cellCapacity()));
        if (!mesh.isLive(c)) continue;
        if (random() % 2) mesh.split(c) || mesh.join(c);
        else mesh.merge(c) || mesh.breakHexagon(c);
    }
}

// What a renderer holds: copies updated only through the dirty ranges (the normals, while the
// stream keeps them, through the vertices' ranges).
struct RendererCopy {
    std::vector<uint32_t> indices;
    std::vector<StreamVertex> vertices;
    std::vector<int16_t> normals;
    void upload(FanStream& stream, const HexMesh& mesh) {
        indices.resize(stream.indices().size(), 0xDEADBEEFu);
        vertices.resize(size_t(mesh.vertexCapacity()));
        normals.resize(4 * size_t(mesh.vertexCapacity()), int16_t(0x7EAD));
        for (const ElementRange& r : stream.dirtyIndices()) {
            ASSERT_LE(size_t(r.first + r.count), stream.indices().size()) << "a dirty range past the used indices";
            std::copy_n(stream.indices().begin() + r.first, r.count, indices.begin() + r.first);
        }
        for (const ElementRange& r : stream.dirtyVertices()) {
            ASSERT_LE(r.first + r.count, mesh.vertexCapacity()) << "a dirty range past the vertex pool";
            std::copy_n(mesh.vertexData() + r.first, r.count, vertices.begin() + r.first);
            if (stream.normalData()) std::copy_n(stream.normalData() + 4 * r.first, 4 * r.count, normals.begin() + 4 * r.first);
        }
        stream.acknowledge();
    }
};

} // namespace

TEST(FanStream, DecodedFansAreExactlyTheMeshTrianglesInBothLayouts) {
    VolcanoStream volcano;
    ASSERT_NE(volcano.field, nullptr);
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    ASSERT_EQ(mesh.checkInvariants(), nullptr);
    const std::vector<Triangle> expected = meshTriangles(mesh);
    EXPECT_EQ(int64_t(expected.size()), mesh.triangleCount());
    EXPECT_EQ(decode(stream), expected);
    stream.setLayout(IndexLayout::Triangles);
    EXPECT_EQ(decode(stream), expected);
}

TEST(FanStream, EverySlotIsItsCellsFanThenRestartsAndNothingExceedsCapacity) {
    VolcanoStream volcano;
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    Geomorph morph;
    std::mt19937 random(7);
    for (int32_t round = 0; round < 20; ++round) {
        randomOperations(mesh, random, 300);
        stream.sync(mesh, morph);
        ASSERT_EQ(stream.indexCount(), mesh.cellCapacity() * FanStream::kFanSlot);
        for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
            const uint32_t* slot = stream.indices().data() + size_t(c) * FanStream::kFanSlot;
            const int32_t expected = !mesh.isLive(c) ? 0 : mesh.cell(c).kind == CellKind::Full ? 8
                                   : mesh.cell(c).kind == CellKind::BoundarySemi ? 5 : 4;
            for (int32_t k = 0; k < FanStream::kFanSlot; ++k) {
                if (k < expected) {
                    ASSERT_NE(slot[k], kRestartIndex) << "cell " << c;
                    ASSERT_LT(int32_t(slot[k]), mesh.vertexCapacity()) << "an index past the vertex pool";
                    ASSERT_TRUE(mesh.isVertexLive(int32_t(slot[k])));
                } else {
                    ASSERT_EQ(slot[k], kRestartIndex) << "cell " << c << " slot index " << k;
                }
            }
        }
    }
}

TEST(FanStream, IncrementalUpdatesEqualARewriteBitForBit) {
    auto field = test::loadFixture(test::kJacksboro);
    ASSERT_NE(field, nullptr);
    HexMesh mesh;
    mesh.reset(*field, Embedding::Exact);
    refineUniformly(mesh, 2);
    FanStream stream;
    stream.attach(mesh);
    Geomorph morph;
    std::mt19937 random(11);
    for (int32_t round = 0; round < 30; ++round) {
        randomOperations(mesh, random, 200);
        stream.sync(mesh, morph);
        ASSERT_EQ(mesh.checkInvariants(), nullptr);
        const std::vector<uint32_t> indices = stream.indices();
        const std::vector<int16_t> normals(stream.normalData(), stream.normalData() + 4 * size_t(mesh.vertexCapacity()));
        stream.attach(mesh); // a rewrite from scratch
        ASSERT_EQ(stream.indices(), indices) << "round " << round;
        for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
            if (!mesh.isVertexLive(v)) continue;
            ASSERT_EQ(std::memcmp(&normals[4 * size_t(v)], stream.normal(v), sizeof(int16_t) * 4), 0)
                << "vertex " << v << " round " << round;
        }
    }
}

TEST(FanStream, NormalsAreUnitUpwardAndAveragedFromTheAdjacentTriangles) {
    VolcanoStream volcano; // its stream wrote the normals
    HexMesh& mesh = volcano.mesh;
    ASSERT_NE(volcano.stream.normalData(), nullptr);
    // Reference: area-weighted face normals summed in double over the decoded triangles.
    std::vector<glm::dvec3> sum(size_t(mesh.vertexCapacity()), glm::dvec3(0.0));
    for (const Triangle& t : meshTriangles(mesh)) {
        const glm::dvec3 a(mesh.vertexPosition(int32_t(t[0]))), b(mesh.vertexPosition(int32_t(t[1]))),
            c(mesh.vertexPosition(int32_t(t[2])));
        const glm::dvec3 n = glm::cross(b - a, c - a);
        for (uint32_t v : t) sum[v] += n;
    }
    for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
        if (!mesh.isVertexLive(v)) continue;
        const int16_t* n = volcano.stream.normal(v);
        const glm::dvec3 got(n[0] / 32767.0, n[1] / 32767.0, n[2] / 32767.0);
        ASSERT_NEAR(glm::length(got), 1.0, 1e-4);
        ASSERT_GT(got.y, 0.0);
        const glm::dvec3 want = glm::normalize(sum[size_t(v)]);
        ASSERT_NEAR(glm::length(got - want), 0.0, 1e-4) << "vertex " << v;
    }
}

TEST(FanStream, TheDirtyRangesCarryEveryChangeToARenderersCopy) {
    VolcanoStream volcano;
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    Geomorph morph;
    morph.setFrames(8);
    RendererCopy gpu;
    gpu.upload(stream, mesh);
    std::mt19937 random(3);
    uint32_t version = stream.version();
    for (int32_t round = 0; round < 25; ++round) {
        randomOperations(mesh, random, round % 5 == 0 ? 0 : 100);
        morph.advance();
        stream.sync(mesh, morph);
        if (round % 5 == 0) {
            EXPECT_EQ(stream.version(), version) << "nothing changed: the version stays";
            EXPECT_TRUE(stream.dirtyIndices().empty());
        } else {
            EXPECT_NE(stream.version(), version);
        }
        version = stream.version();
        gpu.upload(stream, mesh);
        ASSERT_EQ(gpu.indices, stream.indices()) << "round " << round;
        for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
            if (!mesh.isVertexLive(v)) continue;
            ASSERT_EQ(std::memcmp(&gpu.vertices[size_t(v)], &mesh.streamVertex(v), sizeof(StreamVertex)), 0) << "vertex " << v;
            ASSERT_EQ(std::memcmp(&gpu.normals[4 * size_t(v)], stream.normal(v), 4 * sizeof(int16_t)), 0) << "normal of vertex " << v;
        }
    }
}

TEST(FanStream, LevelViewHoldsTheFansOfOneLevelPerRange) {
    VolcanoStream volcano;
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    stream.buildLevelView(mesh, false);
    ASSERT_EQ(stream.levelOffsets().size(), size_t(mesh.maxLevel()) + 2);
    int levelsUsed = 0;
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level) {
        int32_t cells = 0;
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c)) ++cells;
        const auto begin = stream.levelIndices().begin() + stream.levelOffsets()[size_t(level)];
        const auto end = stream.levelIndices().begin() + stream.levelOffsets()[size_t(level) + 1];
        EXPECT_EQ(std::count(begin, end, kRestartIndex), cells) << "level " << level;
        levelsUsed += cells > 0;
    }
    EXPECT_GE(levelsUsed, 3) << "the test mesh should mix levels";
    EXPECT_EQ(stream.levelOffsets().back(), int32_t(stream.levelIndices().size()));
}

TEST(FanStream, OutlineHasEveryCellEdgeOnceAndOnlyWhenAskedFor) {
    VolcanoStream volcano;
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    stream.buildLevelView(mesh, false);
    EXPECT_TRUE(stream.outline().empty()) << "no outline unless the wireframe is shown";
    stream.buildLevelView(mesh, true);
    std::vector<uint64_t> edges;
    const std::vector<uint32_t>& outline = stream.outline();
    for (size_t k = 0; k < outline.size(); k += 2) {
        const uint32_t a = std::min(outline[k], outline[k + 1]), b = std::max(outline[k], outline[k + 1]);
        edges.push_back(uint64_t(a) << 32 | b);
    }
    std::sort(edges.begin(), edges.end());
    EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end()) << "an edge is outlined twice";
    int64_t cellEdges = 0, shared = 0;
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level)
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c))
            for (int32_t slot = 1; slot <= 6; ++slot) {
                if (mesh.cornerVertex(c, slot) == kNone) continue;
                ++cellEdges;
                shared += mesh.cell(c).opposite[slot - 1] != kNone;
            }
    EXPECT_EQ(int64_t(edges.size()), cellEdges - shared / 2);
    const size_t shown = stream.memoryBytes(), outlineBytes = outline.capacity() * sizeof(uint32_t);
    stream.buildLevelView(mesh, false);
    EXPECT_LE(stream.memoryBytes() + outlineBytes, shown) << "the outline's memory is given back when it is hidden";
}

TEST(FanStream, NormalsTurnedOffAndOnAgainEqualNormalsKeptAllAlongBitForBit) {
    auto field = test::loadFixture(test::kJacksboro);
    ASSERT_NE(field, nullptr);
    HexMesh kept, toggled; // the same operations on both; one stream drops its normals for a while
    for (HexMesh* mesh : {&kept, &toggled}) {
        mesh->reset(*field, Embedding::Exact);
        refineUniformly(*mesh, 2);
    }
    FanStream keptStream, toggledStream;
    keptStream.attach(kept);
    toggledStream.attach(toggled);
    Geomorph morph;
    std::mt19937 randomKept(5), randomToggled(5);
    for (int32_t round = 0; round < 12; ++round) {
        if (round == 2) {
            const size_t withNormals = toggledStream.memoryBytes();
            toggledStream.setNormals(false);
            EXPECT_LE(toggledStream.memoryBytes() + size_t(toggled.vertexCapacity()) * (24 + 8), withNormals)
                << "off, the stream keeps no normal sums and no normals";
            EXPECT_EQ(toggledStream.normalData(), nullptr);
        }
        if (round == 9) toggledStream.setNormals(true);
        randomOperations(kept, randomKept, 150);
        randomOperations(toggled, randomToggled, 150);
        keptStream.sync(kept, morph);
        toggledStream.sync(toggled, morph);
        ASSERT_EQ(toggledStream.indices(), keptStream.indices()) << "round " << round;
        if (!toggledStream.normals()) continue;
        for (int32_t v = 0; v < kept.vertexCapacity(); ++v) {
            if (!kept.isVertexLive(v)) continue;
            ASSERT_EQ(std::memcmp(keptStream.normal(v), toggledStream.normal(v), sizeof(int16_t) * 4), 0)
                << "vertex " << v << " round " << round;
        }
    }
}

TEST(FanStream, WithoutNormalsTheDirtyRangesStillCarryEveryPositionAndIndex) {
    VolcanoStream volcano;
    HexMesh& mesh = volcano.mesh;
    FanStream& stream = volcano.stream;
    stream.setNormals(false);
    Geomorph morph;
    morph.setFrames(4);
    RendererCopy gpu;
    gpu.upload(stream, mesh);
    std::mt19937 random(8);
    for (int32_t round = 0; round < 15; ++round) {
        randomOperations(mesh, random, 100);
        morph.advance();
        stream.sync(mesh, morph);
        gpu.upload(stream, mesh);
        ASSERT_EQ(gpu.indices, stream.indices()) << "round " << round;
        for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
            if (!mesh.isVertexLive(v)) continue;
            const StreamVertex &got = gpu.vertices[size_t(v)], &want = mesh.streamVertex(v);
            ASSERT_EQ(std::memcmp(&got.position, &want.position, sizeof want.position), 0) << "vertex " << v;
            ASSERT_EQ(std::memcmp(&got.morphFromHeight, &want.morphFromHeight, sizeof want.morphFromHeight), 0) << "vertex " << v;
            ASSERT_EQ(got.morphKey, want.morphKey) << "vertex " << v;
        }
    }
}
