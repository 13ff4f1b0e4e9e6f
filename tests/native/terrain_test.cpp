// The terrain facade (src/terrain.h): the pieces wired once, settings that survive a mesh
// rebuild, and a frame that leaves the stream in step with the mesh.
#include "terrain.h"

#include <gtest/gtest.h>

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
