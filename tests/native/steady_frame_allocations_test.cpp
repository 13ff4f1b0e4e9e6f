// "Allocate at setup, never per frame" (terrain.h): once a terrain has converged and its pools
// and work lists have grown to what a camera path needs, 1,000 frames of small camera motion
// allocate nothing, through the Terrain facade and through the C ABI's frame call.
//
// The global operator new and delete of this test binary are replaced by counting ones (the
// count is read only around the measured frames).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "api/hexlod.h"
#include "fixture.h"
#include "views.h"

namespace {
std::atomic<int64_t> allocations{0};

void* counted(std::size_t bytes) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    std::abort(); // the core is built without exceptions: nothing would catch std::bad_alloc
}
void* countedAligned(std::size_t bytes, std::align_val_t align) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    const std::size_t a = std::max(std::size_t(align), sizeof(void*));
    void* p = nullptr;
    if (posix_memalign(&p, a, bytes ? bytes : 1) == 0) return p;
    std::abort();
}
} // namespace

void* operator new(std::size_t bytes) { return counted(bytes); }
void* operator new[](std::size_t bytes) { return counted(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept { return counted(bytes); }
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept { return counted(bytes); }
void* operator new(std::size_t bytes, std::align_val_t align) { return countedAligned(bytes, align); }
void* operator new[](std::size_t bytes, std::align_val_t align) { return countedAligned(bytes, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace hexlod {
namespace {

constexpr int32_t kPeriod = 50;          // frames of one loop of the camera path
constexpr int32_t kWarmLoops = 6;        // loops flown before counting
constexpr int32_t kSteadyFrames = 1000;  // frames counted

// A camera over the Grand Canyon circling 20 m around a point 600 m above the rim, looking
// 15 degrees down and swinging its heading by a few degrees: small motion, some cells re-tested,
// split and merged in every loop.
struct Pose {
    glm::dvec3 eye, target;
};
Pose poseAt(const Heightfield& field, int32_t frame) {
    const double w = (field.width() - 1) * field.scale().spacingX, h = (field.height() - 1) * field.scale().spacingY;
    const double a = 2.0 * 3.141592653589793 * double(frame % kPeriod) / kPeriod;
    const glm::dvec3 centre(0.4 * w, field.heightAtPosition(0.4 * w, 0.6 * h) + 600.0, 0.6 * h);
    const glm::dvec3 eye = centre + glm::dvec3(20.0 * std::cos(a), 0.0, 20.0 * std::sin(a));
    const double yaw = 0.6 + 0.05 * std::sin(a), pitch = 0.26;
    const glm::dvec3 forward(std::cos(pitch) * std::sin(yaw), -std::sin(pitch), -std::cos(pitch) * std::cos(yaw));
    return {eye, eye + 1000.0 * forward};
}

View viewOf(const Pose& pose) {
    View view;
    makeView(pose.eye, pose.target, {0, 1, 0}, 0.57735026918962573, 16.0 / 9.0, 1080.0, 1.0, 1e6, view);
    return view;
}

TEST(SteadyFrames, AThousandFramesOfSmallMotionAllocateNothingOnceWarm) {
    auto terrain = test::loadTerrain(test::kGrandCanyon);
    ASSERT_NE(terrain, nullptr);
    ASSERT_EQ(terrain->resetMesh(Embedding::Exact), nullptr);
    TerrainSettings settings = terrain->settings();
    settings.morphFrames = 8; // merges wait for their fades (§7)
    terrain->configure(settings);
    auto frame = [&](int32_t i) {
        terrain->setView(viewOf(poseAt(terrain->field(), i)));
        terrain->updateLod();
        terrain->syncStream();
        terrain->acknowledgeStream(); // the renderer uploaded the dirty ranges
    };
    int32_t updates = 0;
    for (; updates < 1000 && !terrain->converged(); ++updates) frame(0);
    ASSERT_TRUE(terrain->converged());
    for (int32_t i = 0; i < kWarmLoops * kPeriod; ++i) frame(i);
    int64_t operations = 0;
    const int64_t before = allocations.load();
    for (int32_t i = 0; i < kSteadyFrames; ++i) {
        frame(i);
        operations += terrain->refiner().lastUpdate().operations;
    }
    const int64_t allocated = allocations.load() - before;
    EXPECT_EQ(allocated, 0) << "allocations in " << kSteadyFrames << " steady frames";
    EXPECT_GT(operations, 0) << "the camera path should split and merge cells";
}

TEST(SteadyFrames, AThousandFramesThroughTheCAbiAllocateNothingOnceWarm) {
    const auto field = test::loadFixture(test::kGrandCanyon); // for the camera path only
    const std::vector<float> samples = test::readF32(test::kGrandCanyon);
    ASSERT_FALSE(samples.empty());
    hexlod_terrain* t = hexlod_terrain_create(test::kGrandCanyon.width, test::kGrandCanyon.height, HEXLOD_SAMPLE_F32);
    ASSERT_NE(t, nullptr);
    std::memcpy(hexlod_terrain_samples(t), samples.data(), samples.size() * sizeof(float));
    hexlod_scale scale{};
    scale.spacing_x_m = test::kGrandCanyon.spacingX;
    scale.spacing_y_m = test::kGrandCanyon.spacingY;
    ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0);
    ASSERT_EQ(hexlod_terrain_prepare(t, nullptr), 0);
    ASSERT_EQ(hexlod_terrain_reset_mesh(t, nullptr), 0);
    hexlod_settings settings{};
    settings.morph_frames = 8;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    hexlod_frame out{};
    auto frame = [&](int32_t i) {
        const Pose pose = poseAt(*field, i);
        hexlod_camera camera{};
        for (int32_t k = 0; k < 3; ++k) camera.eye[k] = pose.eye[k], camera.target[k] = pose.target[k];
        camera.tan_half_fov_y = 0.57735026918962573;
        camera.aspect = 16.0 / 9.0;
        camera.viewport_height_px = 1080.0;
        camera.near_m = 1.0;
        camera.far_m = 1e6;
        const int32_t result = hexlod_terrain_frame(t, &camera, HEXLOD_FRAME_ALL, &out);
        hexlod_terrain_acknowledge(t);
        return result;
    };
    for (int32_t n = 0; n < 1000 && !out.converged; ++n) ASSERT_EQ(frame(0), 0);
    ASSERT_EQ(out.converged, 1);
    for (int32_t i = 0; i < kWarmLoops * kPeriod; ++i) ASSERT_EQ(frame(i), 0);
    int64_t operations = 0, failed = 0;
    const int64_t before = allocations.load();
    for (int32_t i = 0; i < kSteadyFrames; ++i) {
        failed += frame(i) != 0 ? 1 : 0;
        operations += out.operations;
    }
    const int64_t allocated = allocations.load() - before;
    EXPECT_EQ(failed, 0);
    EXPECT_EQ(allocated, 0) << "allocations in " << kSteadyFrames << " steady frames";
    EXPECT_GT(operations, 0) << "the camera path should split and merge cells";
    hexlod_terrain_destroy(t);
}

} // namespace
} // namespace hexlod
