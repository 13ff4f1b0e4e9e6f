// The terrain facade (src/terrain.h): the pieces wired once, settings that survive a mesh
// rebuild, and a frame that leaves the stream in step with the mesh.
#include "terrain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fixture.h"

using namespace hexlod;

TEST(Terrain, SettingsSurviveAMeshRebuildAndEveryRebuildStartsFromTheBase) {
    auto terrain = test::loadTerrain(test::kVolcano);
    ASSERT_NE(terrain, nullptr);
    EXPECT_FALSE(terrain->hasMesh());
    TerrainSettings settings;
    settings.lod.viewIndependent = true;
    settings.lod.maxError = 2.0;
    settings.morphFrames = 4;
    settings.layout = IndexLayout::Triangles;
    settings.normals = false;
    terrain->configure(settings); // before the mesh exists
    ASSERT_EQ(terrain->resetMesh(Embedding::Exact), nullptr);
    const uint32_t epoch = terrain->meshEpoch();
    const int64_t base = terrain->mesh().triangleCount();
    while (terrain->updateLod().operations > 0) {}
    terrain->syncStream();
    EXPECT_TRUE(terrain->converged());
    EXPECT_GT(terrain->mesh().triangleCount(), base);
    EXPECT_EQ(terrain->mesh().checkInvariants(), nullptr);
    EXPECT_EQ(terrain->stream().indexCount(), terrain->mesh().cellCapacity() * FanStream::kTriangleSlot);

    HeightfieldScale scale = terrain->field().scale();
    scale.spacingX *= 2.0;
    ASSERT_EQ(terrain->setScale(scale), nullptr); // rebuilds the mesh for the new positions
    EXPECT_EQ(terrain->meshEpoch(), epoch + 1);
    EXPECT_EQ(terrain->mesh().triangleCount(), base);
    const TerrainSettings kept = terrain->settings();
    EXPECT_TRUE(kept.lod.viewIndependent);
    EXPECT_EQ(kept.lod.maxError, 2.0);
    EXPECT_EQ(kept.morphFrames, 4);
    EXPECT_EQ(kept.layout, IndexLayout::Triangles);
    EXPECT_FALSE(kept.normals);
    EXPECT_GT(terrain->memoryBytes(), 0u);
}

// Pools sized to what the mesh needs: a rebuilt mesh starts from the base mesh's few records, holding
// none of the memory the refined mesh before it took.
TEST(Terrain, ARebuiltMeshGivesTheLastMeshsMemoryBack) {
    std::unique_ptr<Terrain> terrain = test::loadTerrain(test::kGrandCanyon);
    ASSERT_NE(terrain, nullptr);
    ASSERT_EQ(terrain->resetMesh(Embedding::Exact), nullptr);
    const size_t baseBytes = terrain->mesh().memoryBytes() + terrain->stream().memoryBytes();
    TerrainSettings settings = terrain->settings();
    settings.lod.viewIndependent = true;
    settings.lod.maxError = 1.0;
    terrain->configure(settings);
    while (terrain->updateLod().operations > 0) {}
    terrain->syncStream();
    const size_t refinedBytes = terrain->mesh().memoryBytes() + terrain->stream().memoryBytes();
    const size_t refinedRefiner = terrain->refiner().memoryBytes();
    ASSERT_GT(refinedBytes, 200 * baseBytes) << "a large mesh to give back";
    for (Embedding embedding : {Embedding::Shifted, Embedding::Exact}) { // a rebuild for a new embedding
        ASSERT_EQ(terrain->resetMesh(embedding), nullptr);
        terrain->syncStream();
        EXPECT_LE(terrain->mesh().memoryBytes() + terrain->stream().memoryBytes(), 4 * baseBytes); // base pools and logs
        EXPECT_LT(terrain->refiner().memoryBytes(), refinedRefiner) << "per-cell records given back";
    }
    HeightfieldScale scale = terrain->field().scale();
    scale.spacingY *= 1.5;
    ASSERT_EQ(terrain->setScale(scale), nullptr); // a rebuild for new positions
    terrain->syncStream();
    EXPECT_LE(terrain->mesh().memoryBytes() + terrain->stream().memoryBytes(), 4 * baseBytes); // base pools and logs
}

// Pools sized to what the mesh needs: the pools never shrink by themselves, so after the mesh shrank
// by a quarter the terrain renumbers it densely (Terrain::compact) and every consumer with it.
// A compaction changes no cell and no vertex: the same mesh, the same blends under way, a
// converged mesh stays converged; flying on, the stream stays in step with the mesh.
TEST(Terrain, CompactionGivesTheFreeRecordsBackAndChangesNothingElse) {
    std::unique_ptr<Terrain> terrain = test::loadTerrain(test::kGrandCanyon);
    ASSERT_NE(terrain, nullptr);
    ASSERT_EQ(terrain->resetMesh(Embedding::Exact), nullptr);
    TerrainSettings settings = terrain->settings();
    settings.morphFrames = 8; // merges fade across the compaction
    settings.compactPools = false; // compactions at chosen frames only
    terrain->configure(settings);
    const Heightfield& field = terrain->field();
    const double w = (field.width() - 1) * field.scale().spacingX, h = (field.height() - 1) * field.scale().spacingY;
    auto viewAt = [&](double up) {
        const double x = 0.4 * w, z = 0.6 * h;
        View view;
        EXPECT_TRUE(makeView({x, field.heightAtPosition(x, z) + 300.0 + up, z}, {x + 0.2 * w, field.heightAtPosition(x, z), z - 0.2 * h},
                             {0, 1, 0}, 0.57735026918962573, 16.0 / 9.0, 1080.0, 1.0, 1e9, view));
        return view;
    };
    auto frame = [&](const View& view) {
        terrain->setView(view);
        const UpdateStats stats = terrain->updateLod();
        terrain->syncStream();
        return stats;
    };
    // Down low, then climbing: the mesh shrinks while merges fade.
    for (int32_t k = 0; k < 100 && !terrain->converged(); ++k) frame(viewAt(0.0));
    const int64_t peak = terrain->mesh().triangleCount();
    for (int32_t k = 1; k <= 20; ++k) frame(viewAt(5000.0 * k));
    ASSERT_LT(4 * terrain->mesh().liveCells(), 3 * terrain->mesh().cellCapacity()) << "the mesh shrank by a quarter";
    ASSERT_GT(terrain->refiner().pendingMerges(), 0) << "with merges fading";
    const uint64_t hash = terrain->mesh().hash();
    const int32_t pending = terrain->refiner().pendingMerges();
    const size_t bytes = terrain->memoryBytes();
    std::vector<StreamVertex> drawn;
    for (int32_t v = 0; v < terrain->mesh().vertexCapacity(); ++v)
        if (terrain->mesh().isVertexLive(v)) drawn.push_back(terrain->mesh().streamVertex(v));
    terrain->compact();
    EXPECT_EQ(terrain->renumberings(), 1u);
    EXPECT_EQ(terrain->mesh().hash(), hash);
    EXPECT_EQ(terrain->mesh().checkInvariants(), nullptr);
    EXPECT_EQ(terrain->mesh().liveCells(), terrain->mesh().cellCapacity()) << "dense";
    EXPECT_EQ(terrain->refiner().pendingMerges(), pending) << "every fading merge goes on";
    EXPECT_LT(terrain->memoryBytes(), bytes * 3 / 4);
    ASSERT_EQ(size_t(terrain->mesh().vertexCapacity()), drawn.size());
    for (size_t v = 0; v < drawn.size(); ++v)
        ASSERT_EQ(std::memcmp(&drawn[v], &terrain->mesh().streamVertex(int32_t(v)), sizeof(StreamVertex)), 0)
            << "vertex " << v << ": positions and blends keep their order";
    // High up and holding still until converged with no fade left: a compaction then leaves
    // nothing to do.
    for (int32_t k = 0; k < 400 && !terrain->converged(); ++k) frame(viewAt(30000.0));
    ASSERT_TRUE(terrain->converged());
    const uint64_t still = terrain->mesh().hash();
    terrain->compact();
    const UpdateStats after = frame(viewAt(30000.0));
    EXPECT_EQ(after.operations, 0) << "every margin and state followed its cell";
    EXPECT_TRUE(after.converged);
    terrain->retestEveryCell(); // tested again from its cached bounds (§5.1)
    EXPECT_EQ(frame(viewAt(30000.0)).operations, 0) << "every cached bound followed its cell";
    EXPECT_EQ(terrain->mesh().hash(), still);
    // Down again, compacting on its own when it pays: the stream stays in step with the mesh.
    settings.compactPools = true;
    terrain->configure(settings);
    for (int32_t k = 6; k >= 0; --k) frame(viewAt(5000.0 * k));
    for (int32_t k = 6; k >= 0; --k) frame(viewAt(5000.0 * k)); // and up and down once more
    for (int32_t k = 0; k <= 6; ++k) frame(viewAt(5000.0 * k));
    EXPECT_GT(terrain->mesh().triangleCount(), 0);
    EXPECT_GT(peak, 0);
    EXPECT_EQ(terrain->mesh().checkInvariants(), nullptr);
    const std::vector<uint32_t> indices = terrain->stream().indices();
    HexMesh same = terrain->mesh();
    FanStream fresh; // written afresh for the same mesh (a copy: the stream takes over its change log)
    fresh.attach(same);
    EXPECT_EQ(indices, fresh.indices());
}
