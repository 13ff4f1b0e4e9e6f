// A field whose samples arrive by tiles (field/sample_tiles.h, hexlod_terrain_create_tiled): the
// heights come from the finest level present, the refinement waits for the tiles it needs and
// asks for them, the stream stays watertight while they come, and once they are in the mesh is
// the one the same field loaded whole converges to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "api/hexlod.h"
#include "api/hexlod_diagnostics.h"
#include "api/terrain_handle.h"
#include "field/min_max_pyramid.h"
#include "fixture.h"

using namespace hexlod;

namespace {

constexpr int32_t kTile = 64;

// A pyramid as GDAL's overviews make one: each level half the last (rounded up), each sample
// the mean of the two by two it covers.
struct Pyramid {
    std::vector<std::vector<float>> levels;
    std::vector<int32_t> widths, heights;
};

Pyramid makePyramid(const std::vector<float>& full, int32_t width, int32_t height) {
    Pyramid p;
    p.levels.push_back(full), p.widths.push_back(width), p.heights.push_back(height);
    while (p.widths.back() > kTile || p.heights.back() > kTile) {
        const int32_t w = p.widths.back(), h = p.heights.back(), cw = (w + 1) / 2, ch = (h + 1) / 2;
        const std::vector<float>& fine = p.levels.back();
        std::vector<float> coarse(size_t(cw) * ch);
        for (int32_t v = 0; v < ch; ++v)
            for (int32_t u = 0; u < cw; ++u) {
                double sum = 0.0;
                int32_t n = 0;
                for (int32_t i = 2 * v; i <= std::min(2 * v + 1, h - 1); ++i)
                    for (int32_t j = 2 * u; j <= std::min(2 * u + 1, w - 1); ++j) sum += fine[size_t(i) * w + j], ++n;
                coarse[size_t(v) * cw + u] = float(sum / n);
            }
        p.levels.push_back(std::move(coarse)), p.widths.push_back(cw), p.heights.push_back(ch);
    }
    return p;
}

// Jacksboro's pyramid, made once for the tests that use it (empty levels when the fixture is missing).
const Pyramid& jacksboroPyramid() {
    static const Pyramid pyramid = [] {
        const std::vector<float> data = test::readF32(test::kJacksboro);
        return data.empty() ? Pyramid{{{}}, {0}, {0}} : makePyramid(data, test::kJacksboro.width, test::kJacksboro.height);
    }();
    return pyramid;
}

std::vector<int32_t> dimsOf(const Pyramid& p) {
    std::vector<int32_t> dims;
    for (size_t k = 0; k < p.levels.size(); ++k) dims.insert(dims.end(), {p.widths[k], p.heights[k], kTile, kTile});
    return dims;
}

void writeTile(hexlod_terrain* t, const Pyramid& p, int32_t level, int32_t tx, int32_t ty) {
    float* out = static_cast<float*>(hexlod_terrain_tile_buffer(t, level, tx, ty));
    ASSERT_NE(out, nullptr) << hexlod_last_error();
    const int32_t w = p.widths[size_t(level)], h = p.heights[size_t(level)];
    for (int32_t v = 0; v < kTile; ++v)
        for (int32_t u = 0; u < kTile; ++u) {
            const int32_t j = tx * kTile + u, i = ty * kTile + v;
            out[v * kTile + u] = j < w && i < h ? p.levels[size_t(level)][size_t(i) * w + j] : 0.0f;
        }
    ASSERT_EQ(hexlod_terrain_commit_tile(t, level, tx, ty), 0) << hexlod_last_error();
}

void tilesAcross(const Pyramid& p, int32_t level, int32_t& across, int32_t& down) {
    across = (p.widths[size_t(level)] + kTile - 1) / kTile, down = (p.heights[size_t(level)] + kTile - 1) / kTile;
}

// declared: the whole field's height range, as a file's statistics give it (tiled terrains).
void setUp(hexlod_terrain* t, const test::Fixture& f, int32_t morphFrames, bool declared = false) {
    hexlod_scale scale{};
    scale.spacing_x_m = f.spacingX;
    scale.spacing_y_m = f.spacingY;
    ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0) << hexlod_last_error();
    ASSERT_EQ(hexlod_terrain_prepare(t, nullptr), 0) << hexlod_last_error();
    if (declared) {
        ASSERT_EQ(hexlod_terrain_declare_height_range(t, f.minHeight, f.maxHeight), 0) << hexlod_last_error();
    }
    hexlod_mesh_settings mesh{HEXLOD_EMBEDDING_EXACT};
    ASSERT_EQ(hexlod_terrain_reset_mesh(t, &mesh), 0) << hexlod_last_error();
    hexlod_settings settings{};
    settings.morph_frames = morphFrames;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
}

// A low camera over the south of Jacksboro looking north: near samples at full resolution,
// the far half of the field coarse.
hexlod_camera southCamera(const test::Fixture& f) {
    const double w = (f.width - 1) * double(f.spacingX), d = (f.height - 1) * double(f.spacingY);
    return {{0.3 * w, 900.0, d - 300.0}, {0.35 * w, 400.0, 0.5 * d}, {0, 0, 0}, 0.5, 1.6, 800.0, 1.0, 1e7};
}

hexlod_terrain* tiledWithCoarsest(const Pyramid& p) {
    const std::vector<int32_t> dims = dimsOf(p);
    hexlod_terrain* t = hexlod_terrain_create_tiled(p.widths[0], p.heights[0], HEXLOD_SAMPLE_F32, int32_t(p.levels.size()), dims.data());
    EXPECT_NE(t, nullptr) << hexlod_last_error();
    const int32_t coarsest = int32_t(p.levels.size()) - 1;
    int32_t across, down;
    tilesAcross(p, coarsest, across, down);
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) writeTile(t, p, coarsest, tx, ty);
    return t;
}

// The mesh without its heights: every cell with its kind, level and split counter and the
// lattice points of its vertices, as a sorted list.
std::vector<std::vector<int64_t>> structureOf(const HexMesh& mesh) {
    std::vector<std::vector<int64_t>> cells;
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
        if (!mesh.isLive(c)) continue;
        const Hexagon& h = mesh.cell(c);
        std::vector<int64_t> cell{h.level, int64_t(h.kind), h.splitCount, h.firstVisible};
        const CellCorners corners = mesh.corners(c);
        for (int32_t slot = 0; slot <= 6; ++slot)
            if (corners.vertex[slot] != kNone) cell.push_back(int64_t(latticeKey(mesh.vertexLattice(corners.vertex[slot]))));
        cells.push_back(std::move(cell));
    }
    std::sort(cells.begin(), cells.end());
    return cells;
}

} // namespace

TEST(TiledField, HeightsComeFromTheFinestLevelPresentAndEqualTheWholeFieldOnceItIsIn) {
    const test::Fixture& f = test::kJacksboro;
    const Pyramid& p = jacksboroPyramid();
    ASSERT_FALSE(p.levels[0].empty());
    ASSERT_GE(p.levels.size(), 3u);
    hexlod_terrain* t = tiledWithCoarsest(p);
    setUp(t, f, 0);
    EXPECT_EQ(hexlod_terrain_samples(t), nullptr) << "a tiled terrain has no whole array";
    const auto terrain = test::loadTerrain(f);
    const Heightfield& tiled = t->core->field();
    // Only the coarsest level: bilinear between its samples, so within their range.
    const std::vector<float>& top = p.levels.back();
    const float low = *std::min_element(top.begin(), top.end()), high = *std::max_element(top.begin(), top.end());
    for (int32_t i = 0; i < f.height; i += 7)
        for (int32_t j = 0; j < f.width; j += 5) {
            const float h = tiled.heightAt(j, i);
            {
                EXPECT_GE(h, low);
                EXPECT_LE(h, high);
            }
        }
    // Every full-resolution tile: the samples themselves, bit for bit.
    int32_t across, down;
    tilesAcross(p, 0, across, down);
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) writeTile(t, p, 0, tx, ty);
    for (int32_t i = 0; i < f.height; ++i)
        for (int32_t j = 0; j < f.width; ++j) ASSERT_EQ(tiled.heightAt(j, i), terrain->field().heightAt(j, i)) << j << ", " << i;
    // A full-resolution tile gone: its region reads the finest level left there, the coarsest.
    ASSERT_TRUE(t->core->evictTile(0, 1, 1));
    EXPECT_FALSE(t->core->evictTile(int32_t(p.levels.size()) - 1, 0, 0)) << "the coarsest level stays";
    const float back = tiled.heightAt(kTile + 10, kTile + 10);
    EXPECT_GE(back, low);
    EXPECT_LE(back, high);
    EXPECT_EQ(hexlod_terrain_commit_tile(t, 0, 1, 1), HEXLOD_ERROR) << "an evicted tile has no buffer";
    hexlod_terrain_destroy(t);
}

TEST(TiledField, StreamingStaysWatertightAndConvergesToTheMeshOfTheWholeField) {
    const test::Fixture& f = test::kJacksboro;
    const Pyramid& p = jacksboroPyramid();
    ASSERT_FALSE(p.levels[0].empty());
    const hexlod_camera camera = southCamera(f);

    // The field loaded whole, converged.
    hexlod_terrain* whole = hexlod_terrain_create(f.width, f.height, HEXLOD_SAMPLE_F32);
    std::memcpy(hexlod_terrain_samples(whole), p.levels[0].data(), p.levels[0].size() * sizeof(float));
    setUp(whole, f, 0);
    hexlod_frame out{};
    for (int32_t frame = 0; frame < 200 && !out.converged; ++frame)
        ASSERT_EQ(hexlod_terrain_frame(whole, frame == 0 ? &camera : nullptr, HEXLOD_FRAME_ALL | HEXLOD_FRAME_HASH, &out), 0);
    ASSERT_TRUE(out.converged);
    const uint64_t wholeHash = uint64_t(out.hash_high) << 32 | out.hash_low;
    const auto wholeStructure = structureOf(whole->core->mesh());

    for (const int32_t morph : {0, 8}) {
        hexlod_terrain* t = tiledWithCoarsest(p);
        setUp(t, f, morph, true);
        // Tiles arrive a few a frame, the most needed first, as a fetch queue delivers them.
        int32_t quiet = 0, frame = 0;
        std::vector<int32_t> fetchedByLevel(p.levels.size(), 0);
        for (; frame < 600 && quiet < 3; ++frame) {
            ASSERT_EQ(hexlod_terrain_frame(t, frame == 0 ? &camera : nullptr, HEXLOD_FRAME_ALL | HEXLOD_FRAME_HASH, &out), 0);
            double figures[7] = {};
            ASSERT_EQ(hexlod_diag_check_stream(t, figures), 0) << "frame " << frame << ": " << hexlod_last_error();
            ASSERT_EQ(hexlod_diag_check_mesh(t), 0) << hexlod_last_error();
            const hexlod_tile_want* wants = nullptr;
            const int32_t count = hexlod_terrain_tile_wants(t, &wants);
            ASSERT_GE(count, 0);
            for (int32_t k = 1; k < count; ++k) ASSERT_GE(wants[k - 1].priority_px, wants[k].priority_px) << "most needed first";
            for (int32_t k = 0; k < std::min(count, 3); ++k) {
                writeTile(t, p, wants[k].level, wants[k].tx, wants[k].ty);
                ++fetchedByLevel[size_t(wants[k].level)];
            }
            quiet = count == 0 && out.converged && out.pending_merges == 0 ? quiet + 1 : 0;
        }
        ASSERT_EQ(quiet, 3) << "the tiles stopped coming after " << frame << " frames";
        int32_t across, down;
        tilesAcross(p, 0, across, down);
        EXPECT_GT(fetchedByLevel[0], 0) << "the near ground needs full-resolution tiles";
        EXPECT_LT(fetchedByLevel[0], across * down) << "the far ground does not";
        // The cells are the whole field's; a vertex is at the sample's height where the full
        // resolution came, at the overview's elsewhere (the far, coarse cells).
        EXPECT_TRUE(structureOf(t->core->mesh()) == wholeStructure) << "morph " << morph;
        const HexMesh& mesh = t->core->mesh();
        int32_t exact = 0, fromOverview = 0;
        for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
            if (!mesh.isVertexLive(v)) continue;
            const LatticePoint lp = mesh.vertexLattice(v);
            const int32_t j = std::clamp(sampleColumn(lp), 0, f.width - 1), i = std::clamp(lp.r, 0, f.height - 1);
            float detail;
            if (t->core->field().tiles()->levelIn({j, i, j, i}, detail) == 0) {
                ASSERT_EQ(mesh.vertexPosition(v).y, embedLatticePoint(whole->core->field(), Embedding::Exact, lp).y);
                ++exact;
            } else {
                ++fromOverview;
            }
        }
        EXPECT_GT(exact, 10 * fromOverview);

        // Every full-resolution tile in: the very mesh of the whole field, heights included.
        for (int32_t ty = 0; ty < down; ++ty)
            for (int32_t tx = 0; tx < across; ++tx)
                if (!t->core->field().tiles()->present(0, tx, ty)) writeTile(t, p, 0, tx, ty);
        // (The heights change at the end of the first frame's stream step; its test comes after.)
        for (frame = 0; frame < 100 && (frame < 2 || !(out.converged && out.pending_merges == 0)); ++frame) {
            ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL | HEXLOD_FRAME_HASH, &out), 0);
            ASSERT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << hexlod_last_error();
        }
        EXPECT_EQ(uint64_t(out.hash_high) << 32 | out.hash_low, wholeHash) << "morph " << morph;
        hexlod_terrain_destroy(t);
    }
    hexlod_terrain_destroy(whole);
}

TEST(TiledField, WantsFollowTheViewAndEvictedTilesFallBackWithoutCracks) {
    const test::Fixture& f = test::kJacksboro;
    const Pyramid& p = jacksboroPyramid();
    ASSERT_FALSE(p.levels[0].empty());
    hexlod_terrain* t = tiledWithCoarsest(p);
    // Every overview present: what the view asks for is full-resolution tiles.
    for (int32_t level = 1; level + 1 < int32_t(p.levels.size()); ++level) {
        int32_t across, down;
        tilesAcross(p, level, across, down);
        for (int32_t ty = 0; ty < down; ++ty)
            for (int32_t tx = 0; tx < across; ++tx) writeTile(t, p, level, tx, ty);
    }
    setUp(t, f, 8);
    // A tolerance at which the far half of this small field needs no more than its overviews.
    hexlod_settings settings{};
    settings.morph_frames = 8;
    settings.tau_px = 24.0;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    const hexlod_camera south = southCamera(f);
    hexlod_frame out{};
    auto wantsNow = [&] {
        const hexlod_tile_want* wants = nullptr;
        const int32_t count = hexlod_terrain_tile_wants(t, &wants);
        return std::vector<hexlod_tile_want>(wants, wants + std::max(count, 0));
    };
    // Wanted full-resolution tiles in the north half or the south half of the field.
    auto rowsWanted = [&](const std::vector<hexlod_tile_want>& wants, int32_t& north, int32_t& south) {
        north = south = 0;
        for (const hexlod_tile_want& w : wants) {
            const double scale = double(f.height) / p.heights[size_t(w.level)];
            const double centre = 0.5 * (w.ty * kTile * scale + std::min((w.ty + 1) * kTile * scale, double(f.height)));
            north += centre < 0.5 * f.height;
            south += centre > 0.5 * f.height;
        }
    };
    for (int32_t frame = 0; frame < 30; ++frame) ASSERT_EQ(hexlod_terrain_frame(t, frame == 0 ? &south : nullptr, HEXLOD_FRAME_ALL, &out), 0);
    int32_t north = 0, near = 0;
    const std::vector<hexlod_tile_want> fromSouth = wantsNow();
    ASSERT_FALSE(fromSouth.empty());
    rowsWanted(fromSouth, north, near);
    EXPECT_GT(near, north) << "a camera over the south edge wants the full resolution there first";
    EXPECT_GT(fromSouth[0].ty, 3) << "the most needed tile is under the camera";

    // The same camera over the north edge, looking south: what only the south needed drops out.
    const double w = (f.width - 1) * double(f.spacingX), d = (f.height - 1) * double(f.spacingY);
    const hexlod_camera northCamera{{0.6 * w, 900.0, 300.0}, {0.55 * w, 400.0, 0.5 * d}, {0, 0, 0}, 0.5, 1.6, 800.0, 1.0, 1e7};
    for (int32_t frame = 0; frame < 30; ++frame)
        ASSERT_EQ(hexlod_terrain_frame(t, frame == 0 ? &northCamera : nullptr, HEXLOD_FRAME_ALL, &out), 0);
    const std::vector<hexlod_tile_want> fromNorth = wantsNow();
    ASSERT_FALSE(fromNorth.empty());
    rowsWanted(fromNorth, north, near);
    EXPECT_GT(north, near);
    EXPECT_LT(fromNorth[0].ty, 2);
    const auto wanted = [&](const hexlod_tile_want& x) {
        return std::any_of(fromNorth.begin(), fromNorth.end(), [&](const hexlod_tile_want& y) { return x.level == y.level && x.tx == y.tx && x.ty == y.ty; });
    };
    EXPECT_FALSE(wanted(fromSouth[0])) << "the south's most needed tile is not wanted any more";

    // Every tile it wants comes; then every full-resolution tile goes again: the heights fall
    // back, vertices blend down, and the stream stays watertight throughout.
    for (int32_t frame = 0; frame < 300; ++frame) {
        ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
        const std::vector<hexlod_tile_want> wants = wantsNow();
        if (wants.empty() && out.converged) break;
        for (const hexlod_tile_want& want : wants) writeTile(t, p, want.level, want.tx, want.ty);
    }
    const double refined = out.triangles;
    // A cap of nothing: the terrain lets every tile go but those the mesh stands on, at the next
    // stream step, and the mesh stays watertight and keeps its fine cells.
    const std::vector<TileWant> keep = t->core->tilesInUse();
    ASSERT_FALSE(keep.empty());
    const int32_t coarsest = int32_t(p.levels.size()) - 1;
    const SampleTiles& tiles = *t->core->field().tiles();
    // Every tile of the levels finer than the coarsest.
    const auto eachFinerTile = [&](const auto& visit) {
        for (int32_t level = 0; level < coarsest; ++level) {
            int32_t across, down;
            tilesAcross(p, level, across, down);
            for (int32_t ty = 0; ty < down; ++ty)
                for (int32_t tx = 0; tx < across; ++tx) visit(level, tx, ty);
        }
    };
    int32_t heldBefore = 0;
    eachFinerTile([&](int32_t level, int32_t tx, int32_t ty) { heldBefore += tiles.present(level, tx, ty); });
    for (const TileWant& k : keep) {
        EXPECT_TRUE(tiles.present(k.level, k.tx, k.ty));
        EXPECT_LT(k.level, coarsest);
    }
    EXPECT_EQ(out.tiles_evicted, 0);
    EXPECT_EQ(out.tile_bytes, double(heldBefore) * kTile * kTile * sizeof(float));
    EXPECT_NE(hexlod_terrain_set_tile_cap(t, -1.0), 0) << "a cap below 0";
    EXPECT_NE(hexlod_terrain_set_tile_cap(t, NAN), 0) << "a cap that is not a number";
    ASSERT_EQ(hexlod_terrain_set_tile_cap(t, 0.0), 0) << hexlod_last_error();
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    // What the mesh stood on at that frame's stream step (its LOD update may have moved it).
    const std::vector<TileWant> standsOn = t->core->tilesInUse();
    const auto kept = [&](int32_t level, int32_t tx, int32_t ty) {
        return std::any_of(standsOn.begin(), standsOn.end(), [&](const TileWant& k) { return k.level == level && k.tx == tx && k.ty == ty; });
    };
    int32_t heldAfter = 0;
    eachFinerTile([&](int32_t level, int32_t tx, int32_t ty) {
        heldAfter += tiles.present(level, tx, ty);
        EXPECT_EQ(tiles.present(level, tx, ty), kept(level, tx, ty)) << "level " << level << " tile " << tx << ", " << ty;
    });
    EXPECT_EQ(out.tiles_evicted, heldBefore - heldAfter);
    EXPECT_GT(out.tiles_evicted, 0) << "some tiles were not in use";
    EXPECT_EQ(out.tile_bytes, double(heldAfter) * kTile * kTile * sizeof(float)) << "the tiles in use stay, over the cap";
    for (int32_t frame = 0; frame < 30; ++frame) {
        ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
        ASSERT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << hexlod_last_error();
    }
    EXPECT_GT(out.triangles, 0.8 * refined) << "the cells near the camera stayed";
    // Taken away even from under the mesh: the heights fall back, the cells there merge.
    int32_t across, down, evicted = 0;
    tilesAcross(p, 0, across, down);
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) evicted += t->core->evictTile(0, tx, ty);
    EXPECT_GT(evicted, 0);
    for (int32_t frame = 0; frame < 60; ++frame) {
        ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
        ASSERT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << "frame " << frame << ": " << hexlod_last_error();
    }
    EXPECT_LT(out.triangles, refined) << "cells finer than what is left merged";
    EXPECT_FALSE(wantsNow().empty()) << "and the view asks for the tiles again";
    hexlod_terrain_destroy(t);
}

// A tiled field's height bounds: over the samples loaded while tiles come, the whole field's
// once they are in, and in memory that follows the tiles held, not the field's size.
TEST(TiledField, PyramidBoundsAreTheWholeFieldsOnceTheTilesAreInAndGrowWithTheTilesNotTheField) {
    const test::Fixture& f = test::kJacksboro;
    const Pyramid& p = jacksboroPyramid();
    ASSERT_FALSE(p.levels[0].empty());
    hexlod_terrain* t = tiledWithCoarsest(p);
    setUp(t, f, 0);
    const Heightfield& tiled = t->core->field();
    const auto whole = test::loadTerrain(f);
    MinMaxPyramid wholeBounds, tiledBounds;
    wholeBounds.build(whole->field());
    tiledBounds.build(tiled);
    uint32_t seed = 12345;
    auto next = [&](int32_t n) { seed = seed * 1664525u + 1013904223u; return int32_t((seed >> 8) % uint32_t(n)); };
    // Rectangles of every size, the level a query reads follows from it.
    auto randomRect = [&](SampleRect& r) {
        const int32_t side = 1 + next(next(2) ? 64 : f.width);
        r.j0 = next(f.width), r.i0 = next(f.height), r.j1 = r.j0 + side, r.i1 = r.i0 + 1 + next(side + 1);
    };
    // Only the coarsest level: a bound of the heights the field gives now.
    for (int32_t k = 0; k < 300; ++k) {
        SampleRect r;
        randomRect(r);
        float low, high;
        tiledBounds.query(r.j0, r.i0, r.j1, r.i1, low, high);
        for (int32_t i = r.i0; i <= std::min(r.i1, f.height - 1); ++i)
            for (int32_t j = r.j0; j <= std::min(r.j1, f.width - 1); ++j) {
                ASSERT_GE(tiled.heightAt(j, i), low);
                ASSERT_LE(tiled.heightAt(j, i), high);
            }
    }
    const size_t coarseBytes = tiledBounds.memoryBytes();
    // Every tile in: the very bounds of the field held whole, at every level.
    int32_t across, down;
    tilesAcross(p, 0, across, down);
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) writeTile(t, p, 0, tx, ty);
    tiledBounds.update(tiled, {0, 0, f.width - 1, f.height - 1});
    for (int32_t k = 0; k < 3000; ++k) {
        SampleRect r;
        randomRect(r);
        float wl, wh, tl, th;
        wholeBounds.query(r.j0, r.i0, r.j1, r.i1, wl, wh);
        tiledBounds.query(r.j0, r.i0, r.j1, r.i1, tl, th);
        ASSERT_EQ(tl, wl) << r.j0 << ", " << r.i0 << " to " << r.j1 << ", " << r.i1;
        ASSERT_EQ(th, wh) << r.j0 << ", " << r.i0 << " to " << r.j1 << ", " << r.i1;
    }
    const size_t fullBytes = tiledBounds.memoryBytes();
    EXPECT_GT(fullBytes, coarseBytes) << "the full resolution's fine blocks are kept";
    // The full resolution gone and back: the fine blocks' room is reused.
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) ASSERT_TRUE(t->core->evictTile(0, tx, ty));
    tiledBounds.update(tiled, {0, 0, f.width - 1, f.height - 1});
    for (int32_t ty = 0; ty < down; ++ty)
        for (int32_t tx = 0; tx < across; ++tx) writeTile(t, p, 0, tx, ty);
    tiledBounds.update(tiled, {0, 0, f.width - 1, f.height - 1});
    EXPECT_LT(tiledBounds.memoryBytes(), fullBytes + 340 * 2 * sizeof(float)) << "not one chunk's blocks more";
    hexlod_terrain_destroy(t);

    // A field of 40000² (a national DEM's size) with only its coarsest level: bounds in a
    // fraction of a whole field's pyramid (67 MB at 16-sample blocks).
    std::vector<int32_t> dims;
    for (int32_t side = 40000; ; side = (side + 1) / 2) {
        dims.insert(dims.end(), {side, side, 512, 512});
        if (side <= 512) break;
    }
    const int32_t levels = int32_t(dims.size() / 4);
    hexlod_terrain* big = hexlod_terrain_create_tiled(40000, 40000, HEXLOD_SAMPLE_I16, levels, dims.data());
    ASSERT_NE(big, nullptr) << hexlod_last_error();
    int16_t* top = static_cast<int16_t*>(hexlod_terrain_tile_buffer(big, levels - 1, 0, 0));
    ASSERT_NE(top, nullptr);
    for (int32_t k = 0; k < 512 * 512; ++k) top[k] = int16_t(k % 997);
    ASSERT_EQ(hexlod_terrain_commit_tile(big, levels - 1, 0, 0), 0) << hexlod_last_error();
    hexlod_scale scale{};
    scale.spacing_x_m = scale.spacing_y_m = 1.0;
    ASSERT_EQ(hexlod_terrain_set_scale(big, &scale), 0) << hexlod_last_error();
    ASSERT_EQ(hexlod_terrain_prepare(big, nullptr), 0) << hexlod_last_error();
    MinMaxPyramid bigBounds;
    bigBounds.build(big->core->field());
    EXPECT_LT(bigBounds.memoryBytes(), size_t(1) << 20);
    float low, high;
    bigBounds.query(0, 0, 39999, 39999, low, high);
    EXPECT_EQ(low, 0.0f);
    EXPECT_EQ(high, 996.0f);
    hexlod_terrain_destroy(big);
}

// The terrain owns its tiles: past its cap it lets the least recently used go, a tile that
// comes again counts as used anew, and the figures the frame reports follow.
TEST(TiledField, PastItsCapTheTerrainLetsTheLeastRecentlyUsedTilesGo) {
    const test::Fixture& f = test::kJacksboro;
    const Pyramid& p = jacksboroPyramid();
    ASSERT_FALSE(p.levels[0].empty());
    hexlod_terrain* t = tiledWithCoarsest(p);
    setUp(t, f, 0);
    // From far above: the mesh stays coarse and stands on no full-resolution tile.
    const double w = (f.width - 1) * double(f.spacingX), d = (f.height - 1) * double(f.spacingY);
    const hexlod_camera high{{0.5 * w, 1e6, 0.5 * d}, {0.5 * w, 0.0, 0.5 * d}, {0, 0, -1}, 0.5, 1.6, 800.0, 100.0, 1e8};
    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, &high, HEXLOD_FRAME_ALL, &out), 0) << hexlod_last_error();
    ASSERT_TRUE(t->core->tilesInUse().empty());
    const double tileBytes = double(kTile) * kTile * sizeof(float);
    for (int32_t tx = 0; tx < 4; ++tx) {
        writeTile(t, p, 0, tx, 0);
        ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    }
    EXPECT_EQ(out.tile_bytes, 4 * tileBytes) << "unlimited until a cap is set";
    EXPECT_EQ(out.tiles_evicted, 0);
    const SampleTiles& tiles = *t->core->field().tiles();
    auto held = [&] {
        std::vector<int32_t> columns;
        for (int32_t tx = 0; tx < 4; ++tx)
            if (tiles.present(0, tx, 0)) columns.push_back(tx);
        return columns;
    };
    ASSERT_EQ(hexlod_terrain_set_tile_cap(t, 2.5 * tileBytes), 0) << hexlod_last_error();
    EXPECT_EQ(held().size(), 4u) << "the cap acts at the next frame's stream step";
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    EXPECT_EQ(held(), (std::vector<int32_t>{2, 3})) << "the two that came first went";
    EXPECT_EQ(out.tiles_evicted, 2);
    EXPECT_EQ(out.tile_bytes, 2 * tileBytes);
    // The first comes again: now it is the most recently used.
    writeTile(t, p, 0, 0, 0);
    ASSERT_EQ(hexlod_terrain_set_tile_cap(t, tileBytes), 0);
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    EXPECT_EQ(held(), (std::vector<int32_t>{0}));
    EXPECT_EQ(out.tiles_evicted, 4);
    EXPECT_EQ(out.tile_bytes, tileBytes);
    ASSERT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << hexlod_last_error();
    hexlod_terrain_destroy(t);

    hexlod_terrain* whole = hexlod_terrain_create(8, 8, HEXLOD_SAMPLE_F32);
    ASSERT_NE(whole, nullptr);
    EXPECT_EQ(hexlod_terrain_set_tile_cap(whole, tileBytes), HEXLOD_ERROR);
    EXPECT_NE(std::string(hexlod_last_error()).find("whole"), std::string::npos) << hexlod_last_error();
    hexlod_terrain_destroy(whole);
}

// No-data in a tiled field: the page draws it as holes when asked, from the fourth component of
// the stream's vertex normals. A sample is missing where its own tile says so; over an overview,
// where missing samples weigh half or more of the blend.
TEST(TiledField, NoDataSamplesAreMarkedInTheStreamsNormalsWhereverTheirHeightsComeFrom) {
    constexpr int32_t side = 256;
    std::vector<float> full(size_t(side) * side);
    for (int32_t i = 0; i < side; ++i)
        for (int32_t j = 0; j < side; ++j) {
            const bool hole = j >= 100 && j < 140 && i >= 90 && i < 150;
            full[size_t(i) * side + j] = hole ? NAN : float(200.0 + 30.0 * std::sin(j * 0.05) * std::cos(i * 0.04));
        }
    const Pyramid p = makePyramid(full, side, side); // NaN spreads to every overview sample over it
    ASSERT_EQ(p.levels.size(), 3u);
    hexlod_terrain* t = tiledWithCoarsest(p);
    const test::Fixture f{"synthetic", side, side, 10.0f, 10.0f, 170.0f, 230.0f};
    setUp(t, f, 0);
    const Heightfield& field = t->core->field();
    ASSERT_TRUE(field.anyMissing());
    // Only the coarsest level (4 x 4 samples to a full-resolution one): its samples 25..34 are NaN.
    EXPECT_TRUE(field.sampleMissing(120, 120));
    EXPECT_FALSE(field.sampleMissing(10, 10));
    EXPECT_FALSE(field.sampleMissing(120, 200));
    EXPECT_FALSE(field.sampleMissing(200, 120));

    // Every tile of the full resolution in: the missing samples are the NaN ones, exactly.
    for (int32_t ty = 0; ty < side / kTile; ++ty)
        for (int32_t tx = 0; tx < side / kTile; ++tx) writeTile(t, p, 0, tx, ty);
    for (int32_t i = 0; i < side; ++i)
        for (int32_t j = 0; j < side; ++j) ASSERT_EQ(field.sampleMissing(j, i), std::isnan(full[size_t(i) * side + j])) << j << ", " << i;

    // The stream: m = 1 in every vertex normal over a missing sample, and only there.
    const hexlod_camera camera{{1280.0, 900.0, 2600.0}, {1280.0, 200.0, 1200.0}, {0, 0, 0}, 0.8, 1.6, 800.0, 1.0, 1e6};
    hexlod_frame out{};
    for (int32_t frame = 0; frame < 200 && !(out.converged && out.pending_merges == 0); ++frame)
        ASSERT_EQ(hexlod_terrain_frame(t, frame == 0 ? &camera : nullptr, HEXLOD_FRAME_ALL, &out), 0);
    ASSERT_NE(out.normals_ptr, nullptr);
    const HexMesh& mesh = t->core->mesh();
    int32_t marked = 0, clear = 0;
    for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
        if (!mesh.isVertexLive(v)) continue;
        const LatticePoint lp = mesh.vertexLattice(v);
        const int32_t j = std::clamp(sampleColumn(lp), 0, side - 1), i = std::clamp(lp.r, 0, side - 1);
        const bool hole = std::isnan(full[size_t(i) * side + j]);
        ASSERT_EQ(out.normals_ptr[4 * v + 3], hole ? 32767 : 0) << "vertex at sample " << j << ", " << i;
        ++(hole ? marked : clear);
    }
    EXPECT_GT(marked, 0);
    EXPECT_GT(clear, marked);
    hexlod_terrain_destroy(t);
}

// A void in a streamed field is filled as the page fills one held whole, not with the lowest
// height (a pit with cliff walls): the coarsest level by interpolation across the gap, every
// finer tile from the coarser surface under it. A plane's void is filled with the plane.
TEST(TiledField, VoidsAreFilledFromTheSurfaceAroundThemAtEveryLevel) {
    constexpr int32_t side = 256;
    std::vector<float> full(size_t(side) * side);
    const auto plane = [](int32_t j, int32_t i) { return 1000.0 + 0.5 * j - 0.25 * i; };
    const auto hole = [](int32_t j, int32_t i) { return j >= 90 && j < 170 && i >= 60 && i < 140; };
    for (int32_t i = 0; i < side; ++i)
        for (int32_t j = 0; j < side; ++j) full[size_t(i) * side + j] = hole(j, i) ? NAN : float(plane(j, i));
    const Pyramid p = makePyramid(full, side, side);
    hexlod_terrain* t = tiledWithCoarsest(p);
    setUp(t, {"synthetic", side, side, 10.0f, 10.0f, 900.0f, 1200.0f}, 0);
    const Heightfield& field = t->core->field();
    auto worst = [&] { // over the void (an overview's edge samples stand inside the field's edge: off the plane there)
        double error = 0.0;
        for (int32_t i = 0; i < side; ++i)
            for (int32_t j = 0; j < side; ++j)
                if (hole(j, i)) error = std::max(error, std::abs(field.heightAt(j, i) - plane(j, i)));
        return error;
    };
    EXPECT_LT(worst(), 0.05) << "only the coarsest level: its void interpolated";
    for (int32_t ty = 0; ty < side / kTile; ++ty)
        for (int32_t tx = 0; tx < side / kTile; ++tx) writeTile(t, p, 0, tx, ty);
    EXPECT_LT(worst(), 0.05) << "every full-resolution tile: their voids from the surface under them";
    EXPECT_TRUE(field.sampleMissing(130, 100)) << "still marked (the page's holes)";
    EXPECT_FALSE(field.sampleMissing(80, 100));

    // As pits (for holes: their walls make the refinement follow the void's edge), and back.
    float low = 0.0f, high = 0.0f;
    t->core->field().tiles()->range({0, 0, side - 1, side - 1}, low, high);
    ASSERT_EQ(hexlod_terrain_set_void_fill(t, HEXLOD_VOIDS_LOWEST), 0) << hexlod_last_error();
    const float pit = field.heightAt(130, 100);
    EXPECT_LT(pit, low + 2.0f) << "the lowest height (known when the field was prepared: its coarsest level's)";
    for (int32_t i = 60; i < 140; i += 7)
        for (int32_t j = 90; j < 170; j += 7) ASSERT_EQ(field.heightAt(j, i), pit) << j << ", " << i;
    EXPECT_EQ(field.heightAt(80, 100), float(plane(80, 100))) << "valid samples keep their heights";
    ASSERT_EQ(hexlod_terrain_set_void_fill(t, HEXLOD_VOIDS_SURFACE), 0) << hexlod_last_error();
    EXPECT_LT(worst(), 0.05) << "from the surface again";
    EXPECT_EQ(hexlod_terrain_set_void_fill(t, 2), HEXLOD_ERROR);
    hexlod_terrain_destroy(t);

    hexlod_terrain* whole = hexlod_terrain_create(side, side, HEXLOD_SAMPLE_F32);
    EXPECT_EQ(hexlod_terrain_set_void_fill(whole, HEXLOD_VOIDS_LOWEST), HEXLOD_ERROR) << "a field held whole is filled by its caller";
    hexlod_terrain_destroy(whole);
}

// The page commits the coarsest level before it sets the scale, which names the no-data value:
// preparing the field reads those tiles again, so their voids neither widen the height range
// (to -32768 m) nor stay unfilled.
TEST(TiledField, TilesCommittedBeforeTheScaleNamesNoDataAreReadAgainWhenPrepared) {
    constexpr int32_t side = 128;
    std::vector<float> full(size_t(side) * side);
    for (int32_t i = 0; i < side; ++i)
        for (int32_t j = 0; j < side; ++j) full[size_t(i) * side + j] = j >= 40 && j < 80 && i >= 40 && i < 80 ? -32768.0f : float(500.0 + j);
    const Pyramid p = makePyramid(full, side, side); // -32768 averages with valid heights at the void's rim
    hexlod_terrain* t = tiledWithCoarsest(p);
    hexlod_scale scale{};
    scale.spacing_x_m = scale.spacing_y_m = 10.0;
    scale.has_nodata = 1, scale.nodata_raw = -32768.0;
    ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0) << hexlod_last_error();
    hexlod_field_info info{};
    ASSERT_EQ(hexlod_terrain_prepare(t, &info), 0) << hexlod_last_error();
    EXPECT_GT(info.missing, 0.0);
    EXPECT_GT(info.min_height_m, -1000.0) << "no-data is not a height";
    const Heightfield& field = t->core->field();
    EXPECT_TRUE(field.sampleMissing(60, 60));
    EXPECT_GT(field.heightAt(60, 60), 500.0f) << "the void filled from around it";
    hexlod_terrain_destroy(t);
}
