// The refinement data of paper §5 against brute force: a cell's error bound is the largest
// vertical distance between a sample under its drawn triangles and those triangles, for every
// sample type, both embeddings and odd, non-square fields.
#include "lod/cell_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh/hex_mesh_refine.h"

using namespace hexlod;

namespace {

// Rough but deterministic heights: a ridge plus hashed noise, as raw values of the type.
double rawHeight(int32_t j, int32_t i, SampleType type) {
    uint32_t h = uint32_t(j) * 73856093u ^ uint32_t(i) * 19349663u;
    h = (h ^ (h >> 13)) * 0x5bd1e995u;
    const double noise = double(h >> 8 & 0xFFFF) / 65535.0; // [0, 1]
    const double ridge = std::abs(std::sin(0.11 * j + 0.07 * i));
    const double unit = 0.7 * ridge + 0.3 * noise; // [0, 1]
    switch (type) {
        case SampleType::U8: return std::round(unit * 255.0);
        case SampleType::U16: return std::round(unit * 65535.0);
        case SampleType::I16: return std::round(unit * 60000.0 - 30000.0);
        case SampleType::F32: return unit * 2000.0 - 400.0;
    }
    return 0.0;
}

std::unique_ptr<Heightfield> makeField(int32_t width, int32_t height, SampleType type) {
    auto field = Heightfield::create(width, height, type, nullptr);
    for (int32_t i = 0; i < height; ++i)
        for (int32_t j = 0; j < width; ++j) {
            const double raw = rawHeight(j, i, type);
            const size_t k = size_t(i) * size_t(width) + size_t(j);
            void* samples = field->samples();
            switch (type) {
                case SampleType::U8: static_cast<uint8_t*>(samples)[k] = uint8_t(raw); break;
                case SampleType::U16: static_cast<uint16_t*>(samples)[k] = uint16_t(raw); break;
                case SampleType::I16: static_cast<int16_t*>(samples)[k] = int16_t(raw); break;
                case SampleType::F32: static_cast<float*>(samples)[k] = float(raw); break;
            }
        }
    HeightfieldScale scale;
    scale.spacingX = 30.0;
    scale.spacingY = 25.0;
    scale.heightScale = type == SampleType::F32 ? 1.0 : 0.1;
    scale.heightOffset = type == SampleType::I16 ? 500.0 : 12.5;
    EXPECT_EQ(field->setScale(scale), nullptr);
    EXPECT_EQ(field->prepare(), nullptr);
    return field;
}

struct Brute {
    double error = 0.0;
    float low = 1e30f, high = -1e30f;
    int32_t samples = 0;
};

// Every sample of the field tested against every drawn triangle of the cell.
Brute bruteForce(const HexMesh& mesh, const Heightfield& field, Embedding embedding, int32_t c) {
    Brute b;
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    const uint32_t* fan = mesh.cellFan(c);
    const int32_t n = HexMesh::fanLength(mesh.cell(c));
    for (int32_t k = 1; k + 1 < n; ++k) {
        const glm::vec3 &a = mesh.vertexPosition(int32_t(fan[0])), &p = mesh.vertexPosition(int32_t(fan[k])),
                        &q = mesh.vertexPosition(int32_t(fan[k + 1]));
        const double area = (double(p.x) - a.x) * (double(q.z) - a.z) - (double(q.x) - a.x) * (double(p.z) - a.z);
        if (std::abs(area) < 1e-9) continue;
        for (int32_t i = 0; i < field.height(); ++i) {
            const bool shifted = embedding == Embedding::Shifted && (i & 1) != 0;
            for (int32_t j = 0; j < field.width(); ++j) {
                const double x = float((j + (shifted ? 0.5 : 0.0)) * sx), z = float(i * sy);
                // Barycentric coordinates; a sample a hair outside an edge still counts.
                const double u = ((double(p.x) - x) * (double(q.z) - z) - (double(q.x) - x) * (double(p.z) - z)) / area;
                const double v = ((double(q.x) - x) * (double(a.z) - z) - (double(a.x) - x) * (double(q.z) - z)) / area;
                const double w = 1.0 - u - v;
                if (u < -1e-6 || v < -1e-6 || w < -1e-6) continue;
                const double surface = u * a.y + v * p.y + w * q.y;
                const float h = shifted ? 0.5f * (field.heightClamped(j, i) + field.heightClamped(j + 1, i)) : field.heightAt(j, i);
                b.error = std::max(b.error, std::abs(h - surface));
                b.low = std::min(b.low, h), b.high = std::max(b.high, h);
                ++b.samples;
            }
        }
    }
    return b;
}

TEST(CellBounds, EveryScannedCellsErrorIsTheLargestDistanceOfItsSamplesFromItsTriangles) {
    int32_t checked = 0;
    for (SampleType type : {SampleType::U8, SampleType::U16, SampleType::I16, SampleType::F32}) {
        auto field = makeField(45, 38, type);
        MinMaxPyramid pyramid;
        pyramid.build(*field);
        for (Embedding embedding : {Embedding::Exact, Embedding::Shifted}) {
            HexMesh mesh;
            ASSERT_EQ(mesh.reset(*field, embedding), nullptr);
            for (int32_t round = 0; round < 4; ++round) {
                for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
                    if (!mesh.isLive(c)) continue;
                    const CellError e = computeCellError(*field, embedding, pyramid, shapeOfCell(mesh, c));
                    const Brute b = bruteForce(mesh, *field, embedding, c);
                    if (b.samples == 0) continue;
                    // A bound (never below a sample's distance), and tight: the scan reads the
                    // same samples, so only the rounding to float separates the two.
                    EXPECT_GE(double(e.error), b.error) << int(type) << " cell " << c;
                    EXPECT_LE(double(e.error), b.error * (1.0 + 1e-5) + 1e-4) << int(type) << " cell " << c;
                    EXPECT_LE(e.low, b.low);
                    EXPECT_GE(e.high, b.high);
                    ++checked;
                }
                refineUniformly(mesh, 1);
            }
        }
    }
    EXPECT_GT(checked, 2000);
}

// At step 1 a hexagon's (and a boundary half's) only samples are its corners, so its bound is
// exactly 0 (cell_bounds.cpp skips the scan); a semi-hexagon's long edge runs through its
// hexagon's centre, the one sample it measures.
TEST(CellBounds, StepOneHexagonsHoldOnlyTheirCornersAndSemiHexagonsAreMeasured) {
    auto field = makeField(45, 38, SampleType::F32);
    MinMaxPyramid pyramid;
    pyramid.build(*field);
    for (Embedding embedding : {Embedding::Exact, Embedding::Shifted}) {
        HexMesh mesh;
        ASSERT_EQ(mesh.reset(*field, embedding, 8), nullptr);
        refineUniformly(mesh, 2);                 // step 8 to step 2
        refineNear(mesh, 600.0, 450.0, 300.0, 1); // step 1 there, semi-hexagons around it
        const int32_t hexagons = mesh.liveCells();
        int32_t full = 0, semis = 0, semisWithError = 0;
        for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
            if (!mesh.isLive(c)) continue;
            const CellShape shape = shapeOfCell(mesh, c);
            if (shape.step != 1) continue;
            const CellError e = computeCellError(*field, embedding, pyramid, shape);
            const Brute b = bruteForce(mesh, *field, embedding, c);
            if (shape.kind == CellKind::Semi) {
                // Measured without a scan too (its hexagon's centre): a bound, and as tight.
                EXPECT_GE(double(e.error), b.error) << "semi-hexagon " << c;
                EXPECT_LE(double(e.error), b.error * (1.0 + 1e-5) + 1e-4) << "semi-hexagon " << c;
                EXPECT_LE(e.low, b.low);
                EXPECT_GE(e.high, b.high);
                semisWithError += b.error > 1e-3 ? 1 : 0;
                ++semis;
                continue;
            }
            EXPECT_EQ(e.error, 0.0f) << "cell " << c;
            EXPECT_LE(b.error, 1e-9) << "cell " << c; // the corners, up to the brute force's rounding
            EXPECT_LE(b.samples, 3 * (HexMesh::fanLength(mesh.cell(c)) - 2)) << "cell " << c; // its corners, once per triangle
            EXPECT_LE(e.low, b.low);
            EXPECT_GE(e.high, b.high);
            ++full;
        }
        EXPECT_GT(full, hexagons / 4) << int(embedding);
        EXPECT_GT(semis, 0) << int(embedding);
        EXPECT_GT(semisWithError, 0) << int(embedding);
    }
}

} // namespace
