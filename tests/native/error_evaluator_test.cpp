#include "diagnostics/error_evaluator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fixture.h"

using namespace hexlod;

namespace {

// A mesh as the tests build it: packed x, y, z per vertex (metres) and a triangle list.
struct TestMesh {
    std::vector<float> positions;
    std::vector<uint32_t> indices;

    uint32_t addVertex(double x, double y, double z) {
        positions.insert(positions.end(), {float(x), float(y), float(z)});
        return uint32_t(positions.size() / 3 - 1);
    }
    void addTriangle(uint32_t a, uint32_t b, uint32_t c) { indices.insert(indices.end(), {a, b, c}); }
};

ErrorStats evaluate(const Heightfield& field, const TestMesh& mesh, const ErrorOptions& options = {}) {
    return evaluateMeshError(field, mesh.positions.data(), mesh.positions.size() / 3, 3,
                             mesh.indices.data(), mesh.indices.size(), options);
}

double sx(const Heightfield& f) { return f.scale().spacingX; }
double sy(const Heightfield& f) { return f.scale().spacingY; }

// A grid through every step-th sample (and the last column and row), two triangles per cell
// with alternating diagonals (cell by cell, 6 indices per cell in row order), heights times
// verticalScale.
TestMesh gridMesh(const Heightfield& field, int32_t step, float verticalScale = 1.0f) {
    std::vector<int32_t> cols, rows;
    for (int32_t j = 0; j < field.width() - 1; j += step) cols.push_back(j);
    cols.push_back(field.width() - 1);
    for (int32_t i = 0; i < field.height() - 1; i += step) rows.push_back(i);
    rows.push_back(field.height() - 1);
    TestMesh mesh;
    for (int32_t i : rows)
        for (int32_t j : cols) mesh.addVertex(j * sx(field), field.heightAt(j, i) * verticalScale, i * sy(field));
    const uint32_t nc = uint32_t(cols.size());
    for (uint32_t r = 0; r + 1 < rows.size(); ++r) {
        for (uint32_t c = 0; c + 1 < nc; ++c) {
            const uint32_t a = r * nc + c, b = a + 1, d = a + nc, e = d + 1;
            if ((r + c) % 2 == 0) {
                mesh.addTriangle(a, d, b);
                mesh.addTriangle(b, d, e);
            } else {
                mesh.addTriangle(a, d, e);
                mesh.addTriangle(a, e, b);
            }
        }
    }
    return mesh;
}

// Plane y = c0 + cx*x + cz*z through three points (x, y, z), by Cramer's rule.
struct Plane {
    double c0, cx, cz;
    double at(double x, double z) const { return c0 + cx * x + cz * z; }
};
Plane planeThrough(const double p[3][3]) {
    // Rows (1, x, z) . (c0, cx, cz) = y.
    auto det3 = [](double a, double b, double c, double d, double e, double f, double g, double h, double i) {
        return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    };
    const double d = det3(1, p[0][0], p[0][2], 1, p[1][0], p[1][2], 1, p[2][0], p[2][2]);
    const double d0 = det3(p[0][1], p[0][0], p[0][2], p[1][1], p[1][0], p[1][2], p[2][1], p[2][0], p[2][2]);
    const double dx = det3(1, p[0][1], p[0][2], 1, p[1][1], p[1][2], 1, p[2][1], p[2][2]);
    const double dz = det3(1, p[0][0], p[0][1], 1, p[1][0], p[1][1], 1, p[2][0], p[2][1]);
    return {d0 / d, dx / d, dz / d};
}

// Brute-force statistics over a list of per-sample errors given in row order.
struct BruteStats {
    double max = -1.0, mean = 0.0, p99 = 0.0;
    int32_t worstColumn = -1, worstRow = -1;
};
struct BruteAccumulator {
    std::vector<double> errors;
    BruteStats stats;
    void add(double error, int32_t j, int32_t i) {
        errors.push_back(error);
        if (error > stats.max) {
            stats.max = error;
            stats.worstColumn = j;
            stats.worstRow = i;
        }
    }
    BruteStats finish() {
        double sum = 0.0;
        for (double e : errors) sum += e;
        stats.mean = sum / double(errors.size());
        std::sort(errors.begin(), errors.end());
        stats.p99 = errors[size_t(std::ceil(0.99 * double(errors.size()))) - 1];
        return stats;
    }
};

// Two triangles over the whole rectangle, split along the diagonal from the north-east to
// the south-west corner, with the corner samples' heights.
TestMesh twoTriangleMesh(const Heightfield& field, float verticalScale = 1.0f) {
    const int32_t w = field.width() - 1, h = field.height() - 1;
    TestMesh mesh;
    const uint32_t nw = mesh.addVertex(0, field.heightAt(0, 0) * verticalScale, 0);
    const uint32_t ne = mesh.addVertex(w * sx(field), field.heightAt(w, 0) * verticalScale, 0);
    const uint32_t sw = mesh.addVertex(0, field.heightAt(0, h) * verticalScale, h * sy(field));
    const uint32_t se = mesh.addVertex(w * sx(field), field.heightAt(w, h) * verticalScale, h * sy(field));
    mesh.addTriangle(nw, sw, ne);
    mesh.addTriangle(ne, sw, se);
    return mesh;
}

} // namespace

TEST(ErrorEvaluator, FullResolutionGridOfARealFieldHasZeroErrorAndCoversEverySample) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro, &test::kGrandCanyon}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr) << f->name;
        const ErrorStats stats = evaluate(*field, gridMesh(*field, 1));
        EXPECT_EQ(stats.error, nullptr);
        EXPECT_EQ(stats.maxError, 0.0) << f->name;
        EXPECT_EQ(stats.meanError, 0.0) << f->name;
        EXPECT_EQ(stats.p99Error, 0.0) << f->name;
        EXPECT_EQ(stats.uncovered, 0) << f->name;
        EXPECT_EQ(stats.evaluated, int64_t(f->width) * f->height) << f->name;
    }
}

TEST(ErrorEvaluator, TwoTrianglesOverARealFieldMatchBruteForcePlanesAndLocateTheWorstSample) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro, &test::kGrandCanyon}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr) << f->name;
        const int32_t w = field->width() - 1, h = field->height() - 1;
        const double X = w * sx(*field), Z = h * sy(*field);
        // The same two triangles, as planes solved independently of the evaluator.
        const double north[3][3] = {{0, field->heightAt(0, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(w, 0), 0}};
        const double south[3][3] = {{X, field->heightAt(w, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(w, h), Z}};
        const Plane pn = planeThrough(north), ps = planeThrough(south);
        BruteAccumulator brute;
        for (int32_t i = 0; i <= h; ++i) {
            for (int32_t j = 0; j <= w; ++j) {
                const double x = j * sx(*field), z = i * sy(*field);
                const Plane& plane = (x / X + z / Z <= 1.0) ? pn : ps; // the north-west half
                brute.add(std::abs(plane.at(x, z) - field->heightAt(j, i)), j, i);
            }
        }
        const BruteStats expected = brute.finish();

        const ErrorStats stats = evaluate(*field, twoTriangleMesh(*field));
        EXPECT_EQ(stats.error, nullptr);
        EXPECT_GT(expected.max, 1.0) << f->name; // a real error, not a trivial zero
        EXPECT_NEAR(stats.maxError, expected.max, 1e-3) << f->name;
        EXPECT_NEAR(stats.meanError, expected.mean, 1e-3) << f->name;
        EXPECT_NEAR(stats.p99Error, expected.p99, 1e-3) << f->name;
        EXPECT_EQ(stats.worstColumn, expected.worstColumn) << f->name;
        EXPECT_EQ(stats.worstRow, expected.worstRow) << f->name;
        EXPECT_EQ(stats.evaluated, int64_t(w + 1) * (h + 1)) << f->name;
        EXPECT_EQ(stats.uncovered, 0) << f->name;
    }
}

TEST(ErrorEvaluator, MaxMeanAndP99FollowTheirDefinitions) {
    // 10 x 10 samples with heights 0..99 in row order under a flat mesh at 0: the errors are
    // exactly 0..99, so the max is 99 at (9, 9), the mean 49.5 and the nearest-rank 99th
    // percentile the 99th smallest, 98.
    auto field = Heightfield::create(10, 10, SampleType::F32, nullptr);
    ASSERT_NE(field, nullptr);
    float* samples = static_cast<float*>(field->samples());
    for (int k = 0; k < 100; ++k) samples[k] = float(k);
    ASSERT_EQ(field->prepare(), nullptr);
    TestMesh mesh;
    const uint32_t a = mesh.addVertex(0, 0, 0), b = mesh.addVertex(9, 0, 0);
    const uint32_t c = mesh.addVertex(0, 0, 9), d = mesh.addVertex(9, 0, 9);
    mesh.addTriangle(a, b, c); // clockwise and counter-clockwise on purpose
    mesh.addTriangle(b, c, d);
    const ErrorStats stats = evaluate(*field, mesh);
    EXPECT_EQ(stats.maxError, 99.0);
    EXPECT_EQ(stats.worstColumn, 9);
    EXPECT_EQ(stats.worstRow, 9);
    EXPECT_DOUBLE_EQ(stats.meanError, 49.5);
    EXPECT_EQ(stats.p99Error, 98.0);
    EXPECT_EQ(stats.evaluated, 100); // the diagonal's 10 samples lie in both triangles, counted once
    EXPECT_EQ(stats.uncovered, 0);
}

TEST(ErrorEvaluator, MeshMissingPartOfTheFieldReportsExactlyTheUncoveredSamples) {
    auto field = test::loadFixture(test::kJacksboro);
    ASSERT_NE(field, nullptr);
    const int64_t all = int64_t(field->width()) * field->height();

    // A hole: drop the cells of columns [100, 130) x rows [40, 47) from the full grid. The
    // samples on the hole's rim still belong to neighbouring cells; the 29 x 6 inside do not.
    TestMesh grid = gridMesh(*field, 1);
    const uint32_t cellsPerRow = uint32_t(field->width() - 1);
    TestMesh holed;
    holed.positions = grid.positions;
    for (size_t t = 0; t < grid.indices.size(); t += 6) {
        const uint32_t cell = uint32_t(t / 6), c = cell % cellsPerRow, r = cell / cellsPerRow;
        if (c >= 100 && c < 130 && r >= 40 && r < 47) continue;
        holed.indices.insert(holed.indices.end(), grid.indices.begin() + long(t), grid.indices.begin() + long(t + 6));
    }
    ErrorStats stats = evaluate(*field, holed);
    EXPECT_EQ(stats.uncovered, 29 * 6);
    EXPECT_EQ(stats.evaluated, all - 29 * 6);
    EXPECT_EQ(stats.maxError, 0.0);

    // Two triangles over the western part only, up to x = 100.5 columns: columns 0..100 are in.
    const double X = 100.5 * sx(*field), Z = (field->height() - 1) * sy(*field);
    TestMesh west;
    const uint32_t a = west.addVertex(0, 500, 0), b = west.addVertex(X, 500, 0);
    const uint32_t c = west.addVertex(0, 500, Z), d = west.addVertex(X, 500, Z);
    west.addTriangle(a, c, b);
    west.addTriangle(b, c, d);
    stats = evaluate(*field, west);
    EXPECT_EQ(stats.evaluated, int64_t(101) * field->height());
    EXPECT_EQ(stats.uncovered, all - int64_t(101) * field->height());
    EXPECT_LE(stats.worstColumn, 100);

    // No triangles at all: every sample is uncovered and nothing is evaluated.
    stats = evaluateMeshError(*field, nullptr, 0, 3, nullptr, 0);
    EXPECT_EQ(stats.error, nullptr);
    EXPECT_EQ(stats.evaluated, 0);
    EXPECT_EQ(stats.uncovered, all);
    EXPECT_EQ(stats.worstColumn, -1);
}

TEST(ErrorEvaluator, MeshExtendingPastTheFieldEvaluatesOnlyTheSamplesInside) {
    auto field = test::loadFixture(test::kVolcano);
    ASSERT_NE(field, nullptr);
    const int32_t w = field->width() - 1, h = field->height() - 1;
    // A tilted plane on a coarse grid whose outer cells lie partly or wholly outside the
    // rectangle; the plane is exact on any triangulation, so the brute force needs no mesh.
    const Plane plane{150.0, 0.02, -0.03};
    const double xLines[] = {-40.3 * sx(*field), -3.3 * sx(*field), 0.25 * w * sx(*field), 0.7 * w * sx(*field),
                             (w + 2.5) * sx(*field), (w + 30.0) * sx(*field)};
    const double zLines[] = {-11.0 * sy(*field), -0.6 * sy(*field), 0.5 * h * sy(*field), (h + 0.4) * sy(*field),
                             (h + 25.0) * sy(*field)};
    TestMesh mesh;
    for (double z : zLines)
        for (double x : xLines) mesh.addVertex(x, plane.at(x, z), z);
    const uint32_t nc = 6;
    for (uint32_t r = 0; r + 1 < 5; ++r) {
        for (uint32_t c = 0; c + 1 < nc; ++c) {
            const uint32_t a = r * nc + c, b = a + 1, d = a + nc, e = d + 1;
            mesh.addTriangle(a, d, b);
            mesh.addTriangle(b, d, e);
        }
    }
    // Degenerate triangles through samples, with absurd heights that would show if they were
    // interpolated: three vertices on one line (the diagonal through samples (k, k)), and a
    // repeated vertex.
    const uint32_t p0 = mesh.addVertex(0, 1e5, 0), p1 = mesh.addVertex(10 * sx(*field), -1e5, 10 * sy(*field));
    const uint32_t p2 = mesh.addVertex(20 * sx(*field), 1e5, 20 * sy(*field));
    mesh.addTriangle(p0, p1, p2);
    mesh.addTriangle(p1, p1, p2);

    BruteAccumulator brute;
    for (int32_t i = 0; i <= h; ++i)
        for (int32_t j = 0; j <= w; ++j)
            brute.add(std::abs(plane.at(j * sx(*field), i * sy(*field)) - field->heightAt(j, i)), j, i);
    const BruteStats expected = brute.finish();

    const ErrorStats stats = evaluate(*field, mesh);
    EXPECT_EQ(stats.error, nullptr);
    EXPECT_EQ(stats.evaluated, int64_t(w + 1) * (h + 1));
    EXPECT_EQ(stats.uncovered, 0);
    EXPECT_NEAR(stats.maxError, expected.max, 1e-3);
    EXPECT_NEAR(stats.meanError, expected.mean, 1e-3);
    EXPECT_EQ(stats.worstColumn, expected.worstColumn);
    EXPECT_EQ(stats.worstRow, expected.worstRow);
}

TEST(ErrorEvaluator, SampleOnAnEdgeOfTwoDisagreeingTrianglesKeepsTheLargerError) {
    // A non-conforming mesh (a T-junction crack): two big triangles over columns 0..C, and a
    // full-resolution grid over columns C..W-1. On column C the big triangles' edge is a
    // straight line while the grid is exact, so those samples have two different errors;
    // the evaluator keeps the larger and counts them once. The big triangles come first.
    auto field = test::loadFixture(test::kVolcano);
    ASSERT_NE(field, nullptr);
    const int32_t C = 40, w = field->width() - 1, h = field->height() - 1;
    const double X = C * sx(*field), Z = h * sy(*field);
    TestMesh mesh;
    const uint32_t nw = mesh.addVertex(0, field->heightAt(0, 0), 0), ne = mesh.addVertex(X, field->heightAt(C, 0), 0);
    const uint32_t sw = mesh.addVertex(0, field->heightAt(0, h), Z), se = mesh.addVertex(X, field->heightAt(C, h), Z);
    mesh.addTriangle(nw, sw, ne);
    mesh.addTriangle(ne, sw, se);
    const uint32_t first = uint32_t(mesh.positions.size() / 3), nc = uint32_t(w - C + 1);
    for (int32_t i = 0; i <= h; ++i)
        for (int32_t j = C; j <= w; ++j) mesh.addVertex(j * sx(*field), field->heightAt(j, i), i * sy(*field));
    for (uint32_t r = 0; r < uint32_t(h); ++r) {
        for (uint32_t c = 0; c + 1 < nc; ++c) {
            const uint32_t a = first + r * nc + c, b = a + 1, d = a + nc, e = d + 1;
            mesh.addTriangle(a, d, b);
            mesh.addTriangle(b, d, e);
        }
    }

    const double north[3][3] = {{0, field->heightAt(0, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(C, 0), 0}};
    const double south[3][3] = {{X, field->heightAt(C, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(C, h), Z}};
    const Plane pn = planeThrough(north), ps = planeThrough(south);
    BruteAccumulator brute;
    for (int32_t i = 0; i <= h; ++i) {
        for (int32_t j = 0; j <= w; ++j) {
            const double x = j * sx(*field), z = i * sy(*field);
            const Plane& plane = (x / X + z / Z <= 1.0) ? pn : ps;
            brute.add(j <= C ? std::abs(plane.at(x, z) - field->heightAt(j, i)) : 0.0, j, i);
        }
    }
    const BruteStats expected = brute.finish();
    double columnC = 0.0; // the crack's own largest error, which only the big triangles see
    for (int32_t i = 0; i <= h; ++i)
        columnC = std::max(columnC, std::abs(ps.at(X, i * sy(*field)) - field->heightAt(C, i)));
    ASSERT_GT(columnC, 1.0);

    const ErrorStats stats = evaluate(*field, mesh);
    EXPECT_EQ(stats.evaluated, int64_t(w + 1) * (h + 1));
    EXPECT_EQ(stats.uncovered, 0);
    EXPECT_NEAR(stats.maxError, expected.max, 1e-3);
    EXPECT_NEAR(stats.meanError, expected.mean, 1e-4);
    EXPECT_NEAR(stats.p99Error, expected.p99, 1e-3);
}

TEST(ErrorEvaluator, ShiftedLatticeAtFullResolutionHasTheOddRowSmoothingError) {
    // The "shifted" embedding: even rows' vertices on the samples, odd rows' vertices half a
    // sample to the right, x = (j + 0.5) * sx, with height (h(j) + h(j+1)) / 2. To cover the
    // rectangle, each odd row gets W + 1 vertices, k = 0..W at x = (k - 0.5) * sx with height
    // (h(k-1) + h(k)) / 2 and the column clamped to the field, so the west- and eastmost ones
    // sit half a sample outside with their edge sample's height.
    // Between an even row E (W vertices) and an odd row O (W + 1), above or below it, the
    // triangular lattice is: O[k], O[k+1], E[k] for k = 0..W-1 (E[k] lies between them)
    // and E[j], E[j+1], O[j+1] for j = 0..W-2 (O[j+1] lies between them).
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr);
    const int32_t W = field->width(), H = field->height();
    TestMesh mesh;
    std::vector<uint32_t> rowStart(static_cast<size_t>(H));
    for (int32_t i = 0; i < H; ++i) {
        rowStart[size_t(i)] = uint32_t(mesh.positions.size() / 3);
        if (i % 2 == 0) {
            for (int32_t j = 0; j < W; ++j) mesh.addVertex(j * sx(*field), field->heightAt(j, i), i * sy(*field));
        } else {
            for (int32_t k = 0; k <= W; ++k) {
                const float y = (field->heightClamped(k - 1, i) + field->heightClamped(k, i)) / 2.0f;
                mesh.addVertex((k - 0.5) * sx(*field), y, i * sy(*field));
            }
        }
    }
    for (int32_t i = 0; i + 1 < H; ++i) {
        const uint32_t E = rowStart[size_t(i % 2 == 0 ? i : i + 1)];
        const uint32_t O = rowStart[size_t(i % 2 == 0 ? i + 1 : i)];
        for (uint32_t k = 0; k < uint32_t(W); ++k) mesh.addTriangle(O + k, O + k + 1, E + k);
        for (uint32_t j = 0; j + 1 < uint32_t(W); ++j) mesh.addTriangle(E + j, E + j + 1, O + j + 1);
    }

    // On an odd row a sample lies midway between two vertices: the mesh has
    // (h(j-1) + 2h(j) + h(j+1)) / 4 there, an error of |h(j-1) - 2h(j) + h(j+1)| / 4
    // (with the clamped neighbour at the edges). Even rows are exact.
    BruteAccumulator brute;
    for (int32_t i = 0; i < H; ++i) {
        for (int32_t j = 0; j < W; ++j) {
            double e = 0.0;
            if (i % 2 == 1)
                e = std::abs(double(field->heightClamped(j - 1, i)) - 2.0 * field->heightAt(j, i) +
                             field->heightClamped(j + 1, i)) / 4.0;
            brute.add(e, j, i);
        }
    }
    const BruteStats expected = brute.finish();

    const ErrorStats stats = evaluate(*field, mesh);
    EXPECT_EQ(stats.error, nullptr);
    EXPECT_EQ(stats.evaluated, int64_t(W) * H);
    EXPECT_EQ(stats.uncovered, 0);
    EXPECT_GT(expected.max, 1.0);
    EXPECT_NEAR(stats.maxError, expected.max, 1e-3);
    EXPECT_NEAR(stats.meanError, expected.mean, 1e-3);
    EXPECT_NEAR(stats.p99Error, expected.p99, 1e-3);
    EXPECT_EQ(stats.worstRow % 2, 1);
}

TEST(ErrorEvaluator, VerticalScaleGivesTheSameStatsInUnscaledMetres) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr) << f->name;
        ErrorOptions scaled;
        scaled.verticalScale = 3.0f;
        for (int32_t step : {1, 5}) {
            // A coarse grid has a real error; the full grid stays exactly zero when scaled.
            const ErrorStats plain = evaluate(*field, gridMesh(*field, step));
            const ErrorStats tall = evaluate(*field, gridMesh(*field, step, 3.0f), scaled);
            EXPECT_EQ(tall.error, nullptr);
            EXPECT_NEAR(tall.maxError, plain.maxError, 1e-3) << f->name << " step " << step;
            EXPECT_NEAR(tall.meanError, plain.meanError, 1e-3) << f->name << " step " << step;
            EXPECT_NEAR(tall.p99Error, plain.p99Error, 1e-3) << f->name << " step " << step;
            EXPECT_EQ(tall.worstColumn, plain.worstColumn) << f->name << " step " << step;
            EXPECT_EQ(tall.worstRow, plain.worstRow) << f->name << " step " << step;
            EXPECT_EQ(tall.evaluated, plain.evaluated);
            EXPECT_EQ(tall.uncovered, plain.uncovered);
            if (step == 1) {
                EXPECT_EQ(tall.maxError, 0.0);
            } else {
                EXPECT_GT(tall.maxError, 1.0);
            }
        }
        const ErrorStats plain = evaluate(*field, twoTriangleMesh(*field));
        const ErrorStats tall = evaluate(*field, twoTriangleMesh(*field, 3.0f), scaled);
        EXPECT_NEAR(tall.maxError, plain.maxError, 1e-3) << f->name;
        EXPECT_NEAR(tall.meanError, plain.meanError, 1e-3) << f->name;
    }
}

TEST(ErrorEvaluator, InterleavedVerticesWithNormalsGiveTheSameResultAsPackedPositions) {
    auto field = test::loadFixture(test::kJacksboro);
    ASSERT_NE(field, nullptr);
    const TestMesh packed = gridMesh(*field, 7);
    // x, y, z and a "normal" the evaluator must skip: NaN, which would poison any use of it.
    std::vector<float> interleaved;
    for (size_t v = 0; v < packed.positions.size(); v += 3)
        interleaved.insert(interleaved.end(), {packed.positions[v], packed.positions[v + 1], packed.positions[v + 2],
                                               NAN, NAN, NAN});
    const ErrorStats a = evaluate(*field, packed);
    const ErrorStats b = evaluateMeshError(*field, interleaved.data(), interleaved.size() / 6, 6,
                                           packed.indices.data(), packed.indices.size());
    EXPECT_EQ(b.error, nullptr);
    EXPECT_GT(a.maxError, 1.0);
    EXPECT_EQ(b.maxError, a.maxError);
    EXPECT_EQ(b.p99Error, a.p99Error);
    EXPECT_EQ(b.meanError, a.meanError);
    EXPECT_EQ(b.evaluated, a.evaluated);
    EXPECT_EQ(b.uncovered, a.uncovered);
    EXPECT_EQ(b.worstColumn, a.worstColumn);
    EXPECT_EQ(b.worstRow, a.worstRow);
}

TEST(ErrorEvaluator, SampleStrideEvaluatesEveryStrideThSampleOnly) {
    auto field = test::loadFixture(test::kJacksboro);
    ASSERT_NE(field, nullptr);
    const int32_t stride = 3, w = field->width() - 1, h = field->height() - 1;
    const double X = w * sx(*field), Z = h * sy(*field);
    const double north[3][3] = {{0, field->heightAt(0, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(w, 0), 0}};
    const double south[3][3] = {{X, field->heightAt(w, 0), 0}, {0, field->heightAt(0, h), Z}, {X, field->heightAt(w, h), Z}};
    const Plane pn = planeThrough(north), ps = planeThrough(south);
    BruteAccumulator brute;
    for (int32_t i = 0; i <= h; i += stride) {
        for (int32_t j = 0; j <= w; j += stride) {
            const double x = j * sx(*field), z = i * sy(*field);
            const Plane& plane = (x / X + z / Z <= 1.0) ? pn : ps;
            brute.add(std::abs(plane.at(x, z) - field->heightAt(j, i)), j, i);
        }
    }
    const BruteStats expected = brute.finish();
    ErrorOptions options;
    options.sampleStride = stride;
    const ErrorStats stats = evaluate(*field, twoTriangleMesh(*field), options);
    EXPECT_EQ(stats.error, nullptr);
    EXPECT_EQ(stats.evaluated, int64_t(brute.errors.size()));
    EXPECT_EQ(stats.uncovered, 0);
    EXPECT_NEAR(stats.maxError, expected.max, 1e-3);
    EXPECT_NEAR(stats.meanError, expected.mean, 1e-3);
    EXPECT_NEAR(stats.p99Error, expected.p99, 1e-3);
    EXPECT_EQ(stats.worstColumn, expected.worstColumn);
    EXPECT_EQ(stats.worstRow, expected.worstRow);
}

TEST(ErrorEvaluator, InvalidInputIsReportedAndNothingIsEvaluated) {
    auto field = test::loadFixture(test::kVolcano);
    ASSERT_NE(field, nullptr);
    const TestMesh mesh = twoTriangleMesh(*field);
    const size_t vertices = mesh.positions.size() / 3;
    ErrorOptions options;
    options.verticalScale = 0.0f;
    EXPECT_NE(evaluate(*field, mesh, options).error, nullptr);
    options.verticalScale = 1.0f;
    options.sampleStride = 0;
    EXPECT_NE(evaluate(*field, mesh, options).error, nullptr);
    EXPECT_NE(evaluateMeshError(*field, mesh.positions.data(), vertices, 2, mesh.indices.data(), 6).error, nullptr);
    EXPECT_NE(evaluateMeshError(*field, mesh.positions.data(), vertices, 3, mesh.indices.data(), 5).error, nullptr);
    EXPECT_NE(evaluateMeshError(*field, mesh.positions.data(), vertices - 1, 3, mesh.indices.data(), 6).error, nullptr);
    const ErrorStats bad = evaluateMeshError(*field, mesh.positions.data(), vertices - 1, 3, mesh.indices.data(), 6);
    EXPECT_EQ(bad.evaluated, 0);
    EXPECT_EQ(bad.uncovered, 0);
}

// The evaluator's time on a large field is a benchmark figure (hexlod_bench's full-refinement
// line), not a test; this checks what it computes on a mesh of millions of triangles.
TEST(ErrorEvaluator, ALargeFieldIsEvaluatedWholeAndHasNoErrorAtFullResolution) {
    const int32_t n = 2048;
    auto field = Heightfield::create(n, n, SampleType::F32, nullptr);
    ASSERT_NE(field, nullptr);
    float* samples = static_cast<float*>(field->samples());
    for (int32_t i = 0; i < n; ++i)
        for (int32_t j = 0; j < n; ++j)
            samples[size_t(i) * n + size_t(j)] = float(1000.0 + 300.0 * std::sin(j * 0.013) * std::cos(i * 0.021) +
                                                       20.0 * std::sin(j * 0.37 + i * 0.29));
    HeightfieldScale scale;
    scale.spacingX = 30.0;
    scale.spacingY = 30.0;
    ASSERT_EQ(field->setScale(scale), nullptr);
    ASSERT_EQ(field->prepare(), nullptr);
    for (int32_t step : {2, 1}) {
        const TestMesh mesh = gridMesh(*field, step);
        const ErrorStats stats = evaluate(*field, mesh);
        EXPECT_EQ(stats.uncovered, 0) << "step " << step;
        EXPECT_EQ(stats.evaluated, int64_t(n) * n) << "step " << step;
        // Every other sample skipped: the ripple of 20 m amplitude shows as error.
        if (step == 2) {
            EXPECT_GT(stats.maxError, 1.0);
        } else {
            EXPECT_EQ(stats.maxError, 0.0);
        }
    }
}
