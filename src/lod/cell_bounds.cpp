// Refinement data of paper §5 (Fig. 10), cached per §5.1; see cell_bounds.h.
#include "lod/cell_bounds.h"

#include "lod/float_rounding.h"

#include <algorithm>
#include <cmath>

namespace hexlod {

namespace {

struct Triangle {
    glm::vec3 a, b, c;
};

// The vertices of a shape's fan as hex_mesh.cpp's appendTriangles draws it, each embedded
// once: the centre, then the corners around it (a hexagon, or a boundary half's four); or a
// semi-hexagon's four corners from the one its fan starts at. Returns their number.
int32_t shapeVertices(const Heightfield& field, Embedding embedding, const CellShape& shape, glm::vec3 out[7]) {
    auto lattice = [&](int32_t slot) { return latticeAdd(shape.center, kDirections[wrapSlot(slot) - 1], shape.step); };
    auto embed = [&](LatticePoint p) { return embedLatticePoint(field, embedding, p); };
    const int32_t a = shape.kind == CellKind::Full ? 1 : shape.firstVisible;
    if (shape.kind != CellKind::Semi) {
        const int32_t corners = shape.kind == CellKind::Full ? 6 : 4;
        out[0] = embed(shape.center);
        for (int32_t k = 0; k < corners; ++k) out[1 + k] = embed(lattice(a + k));
        return 1 + corners;
    }
    const LatticePoint points[4] = {lattice(a), lattice(a + 1), lattice(a + 2), lattice(a + 3)};
    const int32_t start = semiFanFromSecondCorner(embedding, points[0], points[1], points[2], points[3]) ? 1 : 0;
    for (int32_t i = 0; i < 4; ++i) out[i] = embed(points[(start + i) % 4]); // as HexMesh::setCorners
    return 4;
}

// The drawn triangles of a shape from its fan's vertices (shapeVertices).
int32_t shapeTriangles(const CellShape& shape, const glm::vec3 v[7], Triangle out[6]) {
    if (shape.kind == CellKind::Full) {
        for (int32_t k = 0; k < 6; ++k) out[k] = {v[0], v[1 + k], v[1 + (k + 1) % 6]};
        return 6;
    }
    if (shape.kind == CellKind::BoundarySemi) {
        for (int32_t k = 0; k < 3; ++k) out[k] = {v[0], v[1 + k], v[2 + k]};
        return 3;
    }
    out[0] = {v[0], v[1], v[2]};
    out[1] = {v[0], v[2], v[3]};
    return 2;
}

// Ceiling and floor of a value well inside the int32 range: the truncation, moved by one when
// it went the wrong way (without SSE4.1 the library's rounding is a long sequence; a row's span
// needs two of them).
int32_t ceilToInt(double v) {
    const int32_t t = int32_t(v);
    return t + (double(t) < v ? 1 : 0);
}
int32_t floorToInt(double v) {
    const int32_t t = int32_t(v);
    return t - (double(t) > v ? 1 : 0);
}

// The plane of a triangle, as a height over the ground: h = ay - kx (x - ax) - kz (z - az).
// ny: y of (b - a) x (c - a), twice the signed ground area. Flat (vertical) when ny is ~0.
struct TrianglePlane {
    double ax, ay, az, kx, kz, ny;
    bool vertical() const { return std::abs(ny) < 1e-12; }
    double height(double x, double z) const { return ay - kz * (z - az) - kx * (x - ax); }
};

TrianglePlane planeOf(const Triangle& t) {
    const double ax = t.a.x, ay = t.a.y, az = t.a.z;
    const double ux = double(t.b.x) - ax, uy = double(t.b.y) - ay, uz = double(t.b.z) - az;
    const double vx = double(t.c.x) - ax, vy = double(t.c.y) - ay, vz = double(t.c.z) - az;
    const double ny = uz * vx - ux * vz;
    if (std::abs(ny) < 1e-12) return {ax, ay, az, 0.0, 0.0, ny};
    const double nx = uy * vz - uz * vy, nz = ux * vy - uy * vx;
    return {ax, ay, az, nx / ny, nz / ny, ny};
}

// One edge of a triangle on the ground, for finding where each sample row crosses it.
struct GroundEdge {
    double zLow, zHigh;   // rows within these (a hair wider) cross the edge
    double xLow, xHigh;   // the edge's x extent: a crossing never lies outside it
    double x0, z0, dxdz;  // x = x0 + (z - z0) * dxdz; dxdz unused for an edge along a row
    bool alongRow;
};

GroundEdge groundEdge(const glm::vec3& a, const glm::vec3& b, double rowEps) {
    const double za = a.z, zb = b.z, xa = a.x, xb = b.x;
    return {std::min(za, zb) - rowEps, std::max(za, zb) + rowEps, std::min(xa, xb), std::max(xa, xb),
            xa, za, za == zb ? 0.0 : (xb - xa) / (zb - za), za == zb};
}

// The samples of one row between columns j0 and j1 against the plane h = c - kx (x - ax):
// the largest distance above and below it and the samples' range. One loop per sample type,
// with the plane linear along the row, keeps the per-sample work to a few multiply-adds.
template <typename Sample>
void scanRow(const Sample* row, int32_t j0, int32_t j1, double sx, double heightScale, double heightOffset, double c,
             double kx, double ax, double& above, double& below, float& low, float& high) {
    for (int32_t j = j0; j <= j1; ++j) {
        // Sample positions rounded as a vertex on the sample stores them (embedding.cpp), so
        // a sample under a vertex has no error from position rounding.
        const double x = float(j * sx);
        const float h = float(double(row[j]) * heightScale + heightOffset); // Heightfield::heightAt
        const double d = h - (c - kx * (x - ax));
        above = std::max(above, d);
        below = std::min(below, d);
        low = std::min(low, h);
        high = std::max(high, h);
    }
}

// Scans the samples inside one triangle: the largest |sample - plane| and the sample range.
// The exact embedding is measured against the original samples; the shifted one against the
// field it stores (§4.7: odd rows half a sample east, heights interpolated), which is what
// its vertices sample and what its full refinement reproduces.
void scanTriangle(const Heightfield& field, Embedding embedding, const Triangle& t, double& error, float& low, float& high) {
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    const TrianglePlane plane = planeOf(t);
    if (plane.vertical()) return;
    const double ax = plane.ax, ay = plane.ay, az = plane.az, kx = plane.kx, kz = plane.kz;
    // Samples within a hair of an edge belong to both triangles: none may fall between cells.
    const double eps = 1e-4;
    const double zMin = std::min({double(t.a.z), double(t.b.z), double(t.c.z)});
    const double zMax = std::max({double(t.a.z), double(t.b.z), double(t.c.z)});
    const int32_t i0 = std::max(0, int32_t(std::ceil(zMin / sy - eps)));
    const int32_t i1 = std::min(field.height() - 1, int32_t(std::floor(zMax / sy + eps)));
    const GroundEdge edges[3] = {groundEdge(t.a, t.b, eps * sy), groundEdge(t.b, t.c, eps * sy), groundEdge(t.c, t.a, eps * sy)};
    const HeightfieldScale& scale = field.scale();
    const double toColumns = 1.0 / sx; // each row's span in columns: a multiplication, not a division
    double above = -1e300, below = 1e300;
    for (int32_t i = i0; i <= i1; ++i) {
        const double z = float(i * sy);
        double xl = 1e300, xr = -1e300;
        for (const GroundEdge& e : edges) {
            if (z < e.zLow || z > e.zHigh) continue;
            if (e.alongRow) {
                xl = std::min(xl, e.xLow), xr = std::max(xr, e.xHigh);
                continue;
            }
            const double x = std::clamp(e.x0 + (z - e.z0) * e.dxdz, e.xLow, e.xHigh);
            xl = std::min(xl, x), xr = std::max(xr, x);
        }
        if (xl > xr) continue;
        const double c = ay - kz * (z - az);
        if (embedding == Embedding::Shifted && (i & 1) != 0) {
            const int32_t j0 = std::max(0, ceilToInt(xl * toColumns - 0.5 - eps));
            const int32_t j1 = std::min(field.width() - 1, floorToInt(xr * toColumns - 0.5 + eps));
            for (int32_t j = j0; j <= j1; ++j) {
                const double x = float((j + 0.5) * sx);
                const float h = 0.5f * (field.heightClamped(j, i) + field.heightClamped(j + 1, i));
                const double d = h - (c - kx * (x - ax));
                above = std::max(above, d), below = std::min(below, d);
                low = std::min(low, h), high = std::max(high, h);
            }
            continue;
        }
        const int32_t j0 = std::max(0, ceilToInt(xl * toColumns - eps));
        const int32_t j1 = std::min(field.width() - 1, floorToInt(xr * toColumns + eps));
        if (field.tiles()) {
            // A tiled field: each height from the level present there (scanRow's arithmetic).
            for (int32_t j = j0; j <= j1; ++j) {
                const double x = float(j * sx);
                const float h = field.heightAt(j, i);
                const double d = h - (c - kx * (x - ax));
                above = std::max(above, d), below = std::min(below, d);
                low = std::min(low, h), high = std::max(high, h);
            }
            continue;
        }
        const size_t rowStart = size_t(i) * size_t(field.width());
        auto scan = [&](const auto* samples) {
            scanRow(samples + rowStart, j0, j1, sx, scale.heightScale, scale.heightOffset, c, kx, ax, above, below, low, high);
        };
        switch (field.type()) {
            case SampleType::U8: scan(static_cast<const uint8_t*>(field.samples())); break;
            case SampleType::U16: scan(static_cast<const uint16_t*>(field.samples())); break;
            case SampleType::I16: scan(static_cast<const int16_t*>(field.samples())); break;
            case SampleType::F32: scan(static_cast<const float*>(field.samples())); break;
        }
    }
    error = std::max({error, above, -below});
}

// A step-1 semi-hexagon (half of a step-1 hexagon, cut along a diameter) holds the samples of
// that hexagon on its side of the cut: its four corners and, when it lies on that side or on
// the cut, the hexagon's centre (Pick's theorem: a step-1 hexagon holds its seven lattice
// points and no other). Only the centre can be off the drawn surface: its distance from the
// triangle it lies in (or lies on the edge of), on the plane scanTriangle uses, and its
// height; nothing when it lies outside the cell or the field.
void measureStepOneSemiCentre(const Heightfield& field, Embedding embedding, const CellShape& shape, const Triangle triangles[2],
                              double& error, float& low, float& high) {
    const int32_t j = sampleColumn(shape.center), i = shape.center.r;
    if (i < 0 || i >= field.height() || j < 0 || j >= field.width()) return;
    const glm::vec3 p = embedLatticePoint(field, embedding, shape.center);
    // The centre is on the cut or half a sample off it: a margin well over the rounding of
    // float positions (a few ulps of the coordinates) and well under that half sample.
    const double margin = 1e-3 * std::min(field.scale().spacingX, field.scale().spacingY) +
                          1e-6 * std::max(std::abs(double(p.x)), std::abs(double(p.z)));
    for (int32_t k = 0; k < 2; ++k) {
        const Triangle& t = triangles[k];
        const TrianglePlane plane = planeOf(t);
        if (plane.vertical()) continue;
        // Inside, or within the margin of an edge: on the inner side of each edge, or close to it.
        const glm::vec3* corners[3] = {&t.a, &t.b, &t.c};
        bool inside = true;
        for (int32_t e = 0; e < 3 && inside; ++e) {
            const glm::vec3 &from = *corners[e], &to = *corners[(e + 1) % 3];
            const double ex = double(to.x) - from.x, ez = double(to.z) - from.z;
            const double side = (ex * (double(p.z) - from.z) - ez * (double(p.x) - from.x)) * (plane.ny > 0.0 ? -1.0 : 1.0);
            inside = side >= -margin * std::sqrt(ex * ex + ez * ez);
        }
        if (!inside) continue;
        const double d = double(p.y) - plane.height(p.x, p.z);
        error = std::max(error, std::abs(d));
        low = std::min(low, p.y), high = std::max(high, p.y);
    }
}

// The columns (half ones on a shifted odd row) and rows a shape's own corners and centre span.
struct LatticeExtent {
    double column0 = 1e300, column1 = -1e300;
    int32_t row0 = INT32_MAX, row1 = INT32_MIN;
    double samples() const { return (column1 - column0 + 1.0) * (double(row1) - row0 + 1.0); }
};

LatticeExtent extentOf(Embedding embedding, const CellShape& shape) {
    LatticeExtent e;
    auto add = [&](LatticePoint p) {
        const double column = embedding == Embedding::Exact ? double(sampleColumn(p)) : p.q + 0.5 * p.r;
        e.column0 = std::min(e.column0, column), e.column1 = std::max(e.column1, column);
        e.row0 = std::min(e.row0, p.r), e.row1 = std::max(e.row1, p.r);
    };
    const int32_t first = shape.kind == CellKind::Full ? 1 : shape.firstVisible;
    const int32_t corners = shape.kind == CellKind::Full ? 6 : 4;
    for (int32_t i = 0; i < corners; ++i) add(latticeAdd(shape.center, kDirections[wrapSlot(first + i) - 1], shape.step));
    if (shape.kind != CellKind::Semi) add(shape.center);
    return e;
}

} // namespace

CellShape shapeOfCell(const HexMesh& mesh, int32_t cell) {
    const Hexagon& h = mesh.cell(cell);
    return {h.kind, h.firstVisible, mesh.cellCenter(cell), mesh.cellStep(cell)};
}

CellShape parentShapeOfCell(const HexMesh& mesh, int32_t cell) {
    CellShape shape = shapeOfCell(mesh, cell);
    shape.step *= 2;
    return shape;
}

namespace {

// Rounded outwards, so that it holds both the exact positions of the samples (x = j * sx) and
// the float ones of the vertices (the nearest float): a float's step is 4 m at 4e7 m.
Footprint footprintOf(const Heightfield& field, const LatticeExtent& e) {
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    return {roundedDown(e.column0 * sx), roundedUp(e.column1 * sx), roundedDown(e.row0 * sy), roundedUp(e.row1 * sy)};
}

} // namespace

Footprint footprintOf(const Heightfield& field, Embedding embedding, const CellShape& shape) {
    return footprintOf(field, extentOf(embedding, shape));
}

SampleRect samplesUnder(const Heightfield& field, const Footprint& f) {
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    return {int32_t(std::floor(f.x0 / sx)), int32_t(std::floor(f.z0 / sy)), int32_t(std::ceil(f.x1 / sx)), int32_t(std::ceil(f.z1 / sy))};
}

SlopeBox slopesUnder(const Heightfield& field, Embedding embedding, const Footprint& f) {
    SlopeBox box;
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    const int32_t j0 = std::max(0, int32_t(std::floor(f.x0 / sx))), j1 = std::min(field.width() - 1, int32_t(std::ceil(f.x1 / sx)));
    const int32_t i0 = std::max(0, int32_t(std::floor(f.z0 / sy))), i1 = std::min(field.height() - 1, int32_t(std::ceil(f.z1 / sy)));
    if (embedding != Embedding::Exact || j1 <= j0 || i1 <= i0 || double(j1 - j0 + 1) * (i1 - i0 + 1) > kExactScanSamples) return box;
    for (int32_t i = i0; i <= i1; ++i)
        for (int32_t j = j0; j <= j1; ++j) {
            const float h = field.heightAt(j, i);
            if (j < j1) {
                const float dx = float((field.heightAt(j + 1, i) - h) / sx);
                box.dxLow = std::min(box.dxLow, dx), box.dxHigh = std::max(box.dxHigh, dx);
            }
            if (i < i1) {
                const float dz = float((field.heightAt(j, i + 1) - h) / sy);
                box.dzLow = std::min(box.dzLow, dz), box.dzHigh = std::max(box.dzHigh, dz);
            }
        }
    return box; // j1 > j0 and i1 > i0: both ranges hold a slope, so the box is known
}

CellError computeCellError(const Heightfield& field, Embedding embedding, const MinMaxPyramid& pyramid,
                           const CellShape& shape) {
    glm::vec3 vertices[7];
    const int32_t vertexCount = shapeVertices(field, embedding, shape, vertices);
    float vertexLow = 1e30f, vertexHigh = -1e30f;
    for (int32_t k = 0; k < vertexCount; ++k) vertexLow = std::min(vertexLow, vertices[k].y), vertexHigh = std::max(vertexHigh, vertices[k].y);
    CellError e{vertexLow, vertexHigh, 0.0f};
    // A hexagon (or boundary half) of step 1: its triangles are elementary triangles of the
    // lattice, whose only samples are their corners (Pick's theorem: no room for another), and
    // the drawn surface passes through them. Its error is exactly 0, which judgeCell() reads as a
    // verdict that no camera changes. (A step-1 semi-hexagon's long edge runs through a sample
    // that is not a corner: it is scanned.)
    if (shape.step == 1 && shape.kind != CellKind::Semi) return e;
    Triangle triangles[6];
    const int32_t count = shapeTriangles(shape, vertices, triangles);
    if (shape.step == 1) { // a semi-hexagon (the hexagons returned above)
        double error = 0.0;
        measureStepOneSemiCentre(field, embedding, shape, triangles, error, e.low, e.high);
        e.error = nextUp(float(error));
        return e;
    }
    const LatticeExtent extent = extentOf(embedding, shape);
    const Footprint f = footprintOf(field, extent);
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    // Counted on the lattice: exact, where the floats' extent grows with the coordinates.
    const double samples = extent.samples();
    const bool outside = f.x1 < 0.0f || f.z1 < 0.0f || f.x0 > roundedUp((field.width() - 1) * sx) ||
                         f.z0 > roundedUp((field.height() - 1) * sy);
    if (outside) {
        // No sample lies under the cell: nothing to approximate.
    } else if (samples <= kExactScanSamples) {
        double error = 0.0;
        for (int32_t t = 0; t < count; ++t) scanTriangle(field, embedding, triangles[t], error, e.low, e.high);
        // Rounded up to the next float: the bound must not shrink in the conversion.
        e.error = nextUp(float(error));
    } else {
        // The drawn surface stays within its vertices' heights, the samples within the
        // pyramid's range over the footprint: their distance is bounded by the larger gap.
        float sampleLow, sampleHigh;
        pyramid.query(int32_t(std::floor(f.x0 / sx)), int32_t(std::floor(f.z0 / sy)), int32_t(std::ceil(f.x1 / sx)),
                      int32_t(std::ceil(f.z1 / sy)), sampleLow, sampleHigh);
        e.error = std::max(sampleHigh - vertexLow, vertexHigh - sampleLow);
        e.low = std::min(e.low, sampleLow);
        e.high = std::max(e.high, sampleHigh);
    }
    return e;
}

} // namespace hexlod
