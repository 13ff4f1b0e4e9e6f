// A tiled field of a world DEM's size (1,296,000 x 626,400 samples at 1″, 512² tiles, 13
// levels: the layout of lib/world_cog_server.js), and one of the largest side the core takes:
// the core opens each in tens of MB, refines from far above and close to the ground near its
// far corner, fed the tiles it asks for, and the mesh keeps every invariant there (paper §4),
// stays watertight, and draws the samples near the camera where they are. The heights are a
// formula, so no tile is stored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "api/hexlod.h"
#include "api/hexlod_diagnostics.h"
#include "api/terrain_handle.h"
#include "lod/cell_bounds.h"

using namespace hexlod;

namespace {

constexpr int32_t kTile = 512;
constexpr double kSpacing = 30.87; // metres: 1″ at the equator

// The heights: a sum of sines in metres, as separable terms so that a tile's samples cost a few
// multiplications each. A column's terms and a row's, computed the same way wherever they are
// asked for, make bit-identical heights.
struct ColumnTerms {
    double a, b, c, d;
};
struct RowTerms {
    double a, b, c, d;
};
constexpr double kTwoPi = 6.283185307179586;
ColumnTerms columnTerms(double x) {
    return {std::sin(x * kTwoPi / 90000.0), std::sin(x * kTwoPi / 6100.0), std::cos(x * kTwoPi / 6100.0), std::sin(x * kTwoPi / 97.0)};
}
RowTerms rowTerms(double y) {
    return {std::cos(y * kTwoPi / 70000.0), std::cos(y * kTwoPi / 6100.0), std::sin(y * kTwoPi / 6100.0), std::sin(y * kTwoPi / 83.0)};
}
// Ridges of 1.2 km, hills of 250 m, and 30 m of detail a few samples wide that only the full
// resolution shows; -1,000 to 4,000 m. As int16 metres.
int16_t rawHeight(const ColumnTerms& x, const RowTerms& y) {
    const double h = 1500.0 + 1200.0 * x.a * y.a + 250.0 * (x.b * y.b + x.c * y.c) + 30.0 * x.d * y.d;
    return int16_t(std::lround(h));
}
int16_t rawHeightAt(double column, double row) { return rawHeight(columnTerms(column), rowTerms(row)); }

struct Level {
    int32_t width, height;
    double scaleX, scaleY;
};

// GDAL's overviews: each level half the last, rounded up, down to one tile.
std::vector<Level> levelsOf(int32_t width, int32_t height) {
    std::vector<Level> levels;
    for (int32_t w = width, h = height;; w = (w + 1) / 2, h = (h + 1) / 2) {
        levels.push_back({w, h, double(width) / w, double(height) / h});
        if (w <= kTile && h <= kTile) break;
    }
    return levels;
}

// Writes and commits a tile: the sample k of a level lies at full-resolution position
// (k + 0.5) * scale - 0.5 (hexlod_terrain_create_tiled).
void feedTile(hexlod_terrain* t, const std::vector<Level>& levels, int32_t level, int32_t tx, int32_t ty) {
    const Level& l = levels[size_t(level)];
    int16_t* out = static_cast<int16_t*>(hexlod_terrain_tile_buffer(t, level, tx, ty));
    ASSERT_NE(out, nullptr) << hexlod_last_error();
    std::vector<ColumnTerms> columns(kTile);
    std::vector<RowTerms> rows(kTile);
    for (int32_t u = 0; u < kTile; ++u) columns[size_t(u)] = columnTerms((tx * kTile + u + 0.5) * l.scaleX - 0.5);
    for (int32_t v = 0; v < kTile; ++v) rows[size_t(v)] = rowTerms((ty * kTile + v + 0.5) * l.scaleY - 0.5);
    for (int32_t v = 0; v < kTile; ++v)
        for (int32_t u = 0; u < kTile; ++u) out[v * kTile + u] = rawHeight(columns[size_t(u)], rows[size_t(v)]);
    ASSERT_EQ(hexlod_terrain_commit_tile(t, level, tx, ty), 0) << hexlod_last_error();
}

double heapBytes() {
    double heap[2] = {};
    EXPECT_EQ(hexlod_diag_heap(heap), 0);
    return heap[0];
}

// Frames with the camera until the mesh converged and wants no tile (at most `frames`), feeding
// up to 48 of the most wanted tiles a frame; the mesh and the stream are checked as it goes.
// Returns the tiles fed.
int32_t flyUntilStill(hexlod_terrain* t, const std::vector<Level>& levels, const hexlod_camera& camera, int32_t frames) {
    hexlod_frame out{};
    int32_t fed = 0, quiet = 0, frame = 0;
    for (; frame < frames && quiet < 3; ++frame) {
        EXPECT_EQ(hexlod_terrain_frame(t, frame == 0 ? &camera : nullptr, HEXLOD_FRAME_ALL, &out), 0) << hexlod_last_error();
        if (frame % 8 == 0) {
            EXPECT_EQ(hexlod_diag_check_mesh(t), 0) << "frame " << frame << ": " << hexlod_last_error();
            EXPECT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << "frame " << frame << ": " << hexlod_last_error();
        }
        const hexlod_tile_want* wants = nullptr;
        const int32_t count = hexlod_terrain_tile_wants(t, &wants);
        EXPECT_GE(count, 0);
        for (int32_t k = 0; k < std::min(count, 48); ++k, ++fed) feedTile(t, levels, wants[k].level, wants[k].tx, wants[k].ty);
        quiet = count == 0 && out.converged && out.pending_merges == 0 ? quiet + 1 : 0;
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_EQ(quiet, 3) << "still refining or wanting tiles after " << frame << " frames";
    EXPECT_EQ(hexlod_diag_check_mesh(t), 0) << hexlod_last_error();
    EXPECT_EQ(hexlod_diag_check_stream(t, nullptr), 0) << hexlod_last_error();
    return fed;
}

// Every live cell's footprint holds its corners and centre, both where the samples are (the
// exact positions, in double) and where the vertices are (floats).
void expectFootprintsHoldTheirPoints(const hexlod_terrain* t) {
    const HexMesh& mesh = t->core->mesh();
    const Heightfield& field = t->core->field();
    int32_t checked = 0;
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
        if (!mesh.isLive(c)) continue;
        const Footprint f = footprintOf(field, mesh.embedding(), shapeOfCell(mesh, c));
        const CellCorners corners = mesh.corners(c);
        for (int32_t v : corners.vertex) {
            if (v == kNone) continue;
            const LatticePoint p = mesh.vertexLattice(v);
            const double x = sampleColumn(p) * kSpacing, z = p.r * kSpacing;
            const glm::vec3& drawn = mesh.vertexPosition(v);
            ASSERT_TRUE(f.x0 <= x && x <= f.x1 && f.z0 <= z && z <= f.z1) << "cell " << c << " at column " << sampleColumn(p) << ", row " << p.r;
            ASSERT_TRUE(f.x0 <= drawn.x && drawn.x <= f.x1 && f.z0 <= drawn.z && drawn.z <= f.z1) << "cell " << c;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
}

// Opens a width x height field, checks its memory, then refines from 2,000 km above its middle
// (fromHigh) and from 300 m above the ground at (j0, i0), checking the mesh and the vertices
// near there.
void openRefineAndCheck(int32_t width, int32_t height, int32_t j0, int32_t i0, bool fromHigh) {
    const std::vector<Level> levels = levelsOf(width, height);
    std::vector<int32_t> dims;
    for (const Level& l : levels) dims.insert(dims.end(), {l.width, l.height, kTile, kTile});
    const double heapBefore = heapBytes();
    hexlod_terrain* t = hexlod_terrain_create_tiled(width, height, HEXLOD_SAMPLE_I16, int32_t(levels.size()), dims.data());
    ASSERT_NE(t, nullptr) << hexlod_last_error();
    const int32_t coarsest = int32_t(levels.size()) - 1;
    feedTile(t, levels, coarsest, 0, 0);
    hexlod_scale scale{};
    scale.spacing_x_m = scale.spacing_y_m = kSpacing;
    ASSERT_EQ(hexlod_terrain_set_scale(t, &scale), 0) << hexlod_last_error();
    ASSERT_EQ(hexlod_terrain_prepare(t, nullptr), 0) << hexlod_last_error();
    ASSERT_EQ(hexlod_terrain_declare_height_range(t, -1000.0, 4000.0), 0) << hexlod_last_error();
    hexlod_mesh_settings mesh{HEXLOD_EMBEDDING_EXACT};
    ASSERT_EQ(hexlod_terrain_reset_mesh(t, &mesh), 0) << hexlod_last_error();
    // Open and drawable: what the core holds for 3.1 million full-resolution tiles is a few tens
    // of MB (dense per-tile arrays made it 285 MB), the coarsest tile's 512 KB included.
    const double opened = heapBytes() - heapBefore;
    EXPECT_LT(opened, 40e6) << "bytes the core allocated to open the world field";
    ::testing::Test::RecordProperty("opened_bytes", std::to_string(int64_t(opened)));
    ASSERT_EQ(hexlod_terrain_set_tile_cap(t, 96e6), 0);

    // From 2,000 km above the middle of the field, looking north at a slant.
    const double midX = 0.5 * width * kSpacing, midZ = 0.5 * height * kSpacing;
    const hexlod_camera high{{midX, 2e6, midZ}, {midX, 0.0, midZ - 1.5e6}, {0, 0, 0}, 0.5, 1.6, 800.0, 1000.0, 1e8};
    const int32_t fedHigh = fromHigh ? flyUntilStill(t, levels, high, 300) : 0;
    if (fromHigh) {
        EXPECT_GT(fedHigh, 0) << "the view from far asks for overviews";
        expectFootprintsHoldTheirPoints(t);
    }

    // 300 m above the ground near the south-east corner, looking towards it: the near ground
    // comes at full resolution.
    const double ground = rawHeightAt(j0, i0);
    const double eyeX = j0 * kSpacing, eyeZ = i0 * kSpacing;
    const hexlod_camera low{{eyeX, ground + 300.0, eyeZ}, {eyeX + 2000.0, ground - 200.0, eyeZ + 1500.0}, {0, 0, 0}, 0.5, 1.6, 800.0, 1.0, 1e7};
    const int32_t fedLow = flyUntilStill(t, levels, low, 600);
    EXPECT_GT(fedLow, 0);
    expectFootprintsHoldTheirPoints(t);

    // The drawn vertices within 1 km of the eye's ground point: each at its sample's exact
    // float position and at the formula's height (the full resolution came), and dense (the
    // 30 m detail needs steps of a sample or two there).
    const HexMesh& m = t->core->mesh();
    int32_t near = 0, finest = 1 << 30;
    for (int32_t v = 0; v < m.vertexCapacity(); ++v) {
        if (!m.isVertexLive(v)) continue;
        const glm::vec3& p = m.vertexPosition(v);
        if (std::hypot(p.x - eyeX, p.z - eyeZ) > 1000.0) continue;
        const LatticePoint lp = m.vertexLattice(v);
        const int32_t j = sampleColumn(lp), i = lp.r;
        ASSERT_TRUE(j >= 0 && j < width && i >= 0 && i < height);
        ASSERT_EQ(p.x, float(j * kSpacing)) << "column " << j;
        ASSERT_EQ(p.z, float(i * kSpacing)) << "row " << i;
        ASSERT_EQ(p.y, float(rawHeightAt(j, i))) << "column " << j << ", row " << i;
        ++near;
    }
    for (int32_t c = 0; c < m.cellCapacity(); ++c) {
        if (!m.isLive(c)) continue;
        const LatticePoint centre = m.cellCenter(c);
        if (std::hypot(sampleColumn(centre) * kSpacing - eyeX, centre.r * kSpacing - eyeZ) <= 1000.0) finest = std::min(finest, m.cellStep(c));
    }
    EXPECT_GT(near, 300) << "vertices within 1 km of the camera";
    EXPECT_LE(finest, 2) << "the finest cell step near the camera";

    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    ::testing::Test::RecordProperty("tiles_fed", std::to_string(fedHigh + fedLow));
    ::testing::Test::RecordProperty("triangles", std::to_string(int64_t(out.triangles)));
    hexlod_terrain_destroy(t);
}

} // namespace

// The world at 1″: near column 1,290,000, row 620,000 (4e7 m east).
TEST(WorldField, OpensInTensOfMegabytesRefinesFromFarAndNearAndDrawsTheSamplesWhereTheyAre) {
    ASSERT_EQ(levelsOf(1296000, 626400).size(), 13u);
    openRefineAndCheck(1296000, 626400, 1290000, 620000, true);
}

// The largest side (kMaxTiledFieldSide, 2^21): 16.8 million full-resolution tiles, grouped 2 x 2
// a region (SampleTiles::kMaxRegions); the lattice reaches 2^21 + 2^19 columns, where latticeAt
// still recovers every vertex. Straight to the ground (from 2,000 km the view of this field
// wants 300 MB of tiles).
TEST(WorldField, TheLargestSideGroupsItsTilesIntoRegionsAndDrawsItsSamplesToTheFarCorner) {
    openRefineAndCheck(kMaxTiledFieldSide, kMaxTiledFieldSide, kMaxTiledFieldSide - 6000, kMaxTiledFieldSide - 5000, false);
}
