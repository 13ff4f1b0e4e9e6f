// Geomorphing (paper §7): new vertices start on their parent edge and blend to their place in
// n frames; a merge frees only vertices that have faded out; blends finish; the whole thing is
// deterministic under the frame clock; and it cuts the popping the meter measures.
#include "stream/geomorph.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include <glm/geometric.hpp>

#include "stream/fan_stream.h"
#include "fixture.h"
#include "hex_mesh_util.h"
#include "diagnostics/popping_meter.h"
#include "lod/refiner.h"

using namespace hexlod;

namespace {

constexpr double kTanHalf60 = 0.57735026918962573;

View viewFrom(const glm::dvec3& eye, const glm::dvec3& target) {
    View view;
    EXPECT_TRUE(makeView(eye, target, {0, 1, 0}, kTanHalf60, 16.0 / 9.0, 1080.0, 1.0, 1e9, view));
    return view;
}

// The page's loop in miniature: the terrain facade (mesh, refiner, blends and stream wired as
// the C ABI wires them), with names for its pieces.
struct Lod {
    std::unique_ptr<Terrain> terrain;
    const HexMesh& mesh;
    const Refiner& refiner;
    const Geomorph& morph;
    Lod(const test::Fixture& fixture, int32_t frames, int32_t maxOperations)
        : terrain(test::loadTerrain(fixture)), mesh(terrain->mesh()), refiner(terrain->refiner()), morph(terrain->morph()) {
        terrain->resetMesh(Embedding::Exact);
        TerrainSettings settings = terrain->settings();
        settings.lod.maxOperations = maxOperations;
        settings.morphFrames = frames;
        terrain->configure(settings);
    }
    void frame(const View& view) {
        terrain->setView(view);
        terrain->updateLod();
        terrain->syncStream();
    }
};

// A camera path over the Grand Canyon: in low towards the rim, along it, then up and away.
std::vector<View> flight(const Heightfield& f, int32_t frames) {
    const double w = (f.width() - 1) * f.scale().spacingX, h = (f.height() - 1) * f.scale().spacingY;
    std::vector<View> views;
    for (int32_t i = 0; i < frames; ++i) {
        const double t = double(i) / double(frames - 1);
        const double x = w * (0.2 + 0.5 * t), z = h * (0.8 - 0.4 * t);
        const double above = t < 0.6 ? 400.0 : 400.0 + (t - 0.6) * 40000.0;
        const glm::dvec3 eye(x, f.heightAtPosition(x, z) + above, z);
        views.push_back(viewFrom(eye, {x + 0.2 * w, f.heightAtPosition(x + 0.2 * w, z - 0.2 * h), z - 0.2 * h}));
    }
    return views;
}

} // namespace

TEST(Geomorph, NewVerticesStartOnTheirParentEdgeAndArriveAfterNFrames) {
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr);
    const int32_t n = 6;
    Lod lod(test::kGrandCanyon, n, 400);
    const std::vector<View> views = flight(*field, 20);
    lod.frame(views[0]);
    // The vertices of the first frame's splits, as drawn in that frame.
    std::vector<int32_t> born;
    const test::ParentFinder parentsOf(lod.mesh);
    for (int32_t v = 0; v < lod.mesh.vertexCapacity(); ++v) {
        if (!lod.mesh.isVertexLive(v)) continue;
        const VertexParents parents = parentsOf(v);
        if (parents.a == kNone) continue;
        const StreamVertex& sv = lod.mesh.streamVertex(v);
        ASSERT_EQ(lod.morph.weight(sv), 0.0f) << "a new vertex is drawn on the coarser surface in its first frame";
        const glm::vec3 below = Geomorph::coarserSurface(lod.mesh, v, parents, [&](int32_t u) { return lod.morph.displayed(lod.mesh.streamVertex(u)); });
        ASSERT_LT(std::abs(lod.morph.displayed(sv).y - below.y), 1e-3f) << "it starts on the coarser surface";
        ASSERT_LT(std::abs(below.x - sv.position.x) + std::abs(below.z - sv.position.z), 1e-2f)
            << "which lies straight below or above it: the blend is vertical, so a start height is enough";
        float w[3];
        Geomorph::coarserWeights(lod.mesh, v, parents, w);
        for (float weight : w) ASSERT_GE(weight, -1e-4f) << "the coarser triangle holds it";
        born.push_back(v);
    }
    ASSERT_GT(born.size(), 10u);
    for (int32_t f = 1; f <= n; ++f) {
        lod.frame(views[0]); // the camera holds still
        for (int32_t v : born) {
            if (!lod.mesh.isVertexLive(v)) continue;
            const float w = lod.morph.weight(lod.mesh.streamVertex(v));
            ASSERT_FLOAT_EQ(w, std::min(1.0f, float(f) / float(n))) << "linear in frames";
        }
    }
    for (int32_t v : born) {
        if (lod.mesh.isVertexLive(v)) {
            ASSERT_EQ(lod.morph.displayed(lod.mesh.streamVertex(v)), lod.mesh.vertexPosition(v));
        }
    }
}

TEST(Geomorph, MergesFreeOnlyFadedVerticesAndEveryBlendFinishes) {
    auto field = test::loadFixture(test::kGrandCanyon);
    const int32_t n = 5;
    // The stream's part done here, with our own vertex log to see what each update frees.
    HexMesh mesh;
    mesh.reset(*field, Embedding::Exact);
    Refiner refiner;
    refiner.attach(mesh, *field);
    Geomorph morph;
    morph.setFrames(n);
    refiner.setVertexFades(&morph);
    refiner.settings().maxOperations = 300;
    std::vector<int32_t> log;
    mesh.setVertexLog(&log);
    mesh.setDeferVertexReuse(true);
    int64_t freed = 0, mergesDeferred = 0;
    int32_t quiet = 0; // updates in a row, holding still, converged and no merge fading
    const std::vector<View> views = flight(*field, 90);
    for (size_t i = 0; i < views.size() + 400; ++i) {
        refiner.setView(views[std::min(i, views.size() - 1)]); // then hold still at the end
        morph.advance(); // the clock Terrain::updateLod ticks
        const UpdateStats stats = refiner.update();
        mergesDeferred += refiner.pendingMerges();
        for (size_t k = 0; k < log.size(); ++k) {
            const int32_t entry = log[k];
            if (entry >= 0) { // v, a, b, across
                if (mesh.isVertexLive(entry)) morph.blendIn(mesh, entry, {log[k + 1], log[k + 2], log[k + 3]});
                k += 3;
                continue;
            }
            ++freed;
            const StreamVertex& gone = mesh.streamVertex(~entry); // reuse is deferred: still its data
            ASSERT_TRUE(morph.fadedOut(gone)) << "a merge freed a vertex that was still drawn off the coarser surface";
        }
        log.clear();
        mesh.releaseFreedVertices();
        if (i % 10 == 0) {
            ASSERT_EQ(mesh.checkInvariants(), nullptr);
        }
        // Converged does not wait for fades (a fade changes no cell): hold still until they are done too. A
        // merge called off reverses its fade, which takes n more updates after the last one.
        // Once converged with nothing fading, a camera holding still leaves the mesh alone (a
        // merge called off is tested again before an update reports converged).
        if (quiet > 0) {
            ASSERT_EQ(stats.operations, 0) << "update " << i << " after the view had converged";
            ASSERT_EQ(refiner.pendingMerges(), 0) << "update " << i << " after the view had converged";
        }
        quiet = i >= views.size() && stats.converged && refiner.pendingMerges() == 0 ? quiet + 1 : 0;
        if (quiet > n) break;
    }
    ASSERT_TRUE(refiner.lastUpdate().converged);
    EXPECT_GT(freed, 100) << "flying away should merge";
    EXPECT_GT(mergesDeferred, 0);
    EXPECT_EQ(refiner.pendingMerges(), 0) << "no merge is left waiting";
    for (int32_t v = 0; v < mesh.vertexCapacity(); ++v)
        if (mesh.isVertexLive(v)) {
            ASSERT_EQ(morph.weight(mesh.streamVertex(v)), 1.0f) << "every blend has finished: vertex " << v;
        }
}

TEST(Geomorph, AFlightIsDeterministicUnderTheFrameClock) {
    auto field = test::loadFixture(test::kGrandCanyon);
    const std::vector<View> views = flight(*field, 60);
    auto run = [&](std::vector<StreamVertex>& vertices) {
        Lod lod(test::kGrandCanyon, 8, 150);
        for (const View& view : views) lod.frame(view);
        vertices.assign(lod.mesh.vertexData(), lod.mesh.vertexData() + lod.mesh.vertexCapacity());
        return lod.mesh.hash();
    };
    std::vector<StreamVertex> a, b;
    const uint64_t first = run(a), second = run(b);
    EXPECT_EQ(first, second);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(StreamVertex)), 0);
    std::printf("agree: geomorph-flight-grandcanyon %016llx\n", (unsigned long long)first);
}

TEST(Geomorph, BlendingCutsTheLargestJumpOnScreen) {
    auto field = test::loadFixture(test::kGrandCanyon);
    const std::vector<View> views = flight(*field, 90);
    auto largestJump = [&](int32_t frames) {
        Lod lod(test::kGrandCanyon, frames, 0);
        for (int32_t i = 0; i < 200 && !lod.refiner.lastUpdate().converged; ++i) lod.frame(views[0]); // as loaded
        for (int32_t i = 0; i < frames; ++i) lod.frame(views[0]); // and its blends done
        PoppingMeter meter;
        meter.follow(lod.terrain->meshEpoch(), lod.terrain->renumberings(), lod.terrain->lastRenumbering());
        meter.measure(lod.mesh, lod.morph, views[0], 1.0);
        double worst = 0.0;
        for (const View& view : views) {
            lod.frame(view);
            meter.follow(lod.terrain->meshEpoch(), lod.terrain->renumberings(), lod.terrain->lastRenumbering());
            worst = std::max(worst, meter.measure(lod.mesh, lod.morph, view, 1.0).maxJumpPx);
        }
        return worst;
    };
    const double without = largestJump(0), with = largestJump(8);
    std::printf("popping on the Grand Canyon flight: %.3f px without geomorphing, %.3f px with 8 frames\n", without, with);
    EXPECT_GT(without, 1.0) << "without blending, refinement pops by about tau or more";
    EXPECT_LT(with, without / 3.0);
}
