// Diagnostics of paper §5: the error evaluator; see error_evaluator.h.
#include "diagnostics/error_evaluator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

namespace hexlod {
namespace {

// A sample counts as inside a triangle while each of its barycentric weights is at least
// -kInsideEps: a sample on an edge (or within float rounding of it) is not lost to the
// rounding of the edge functions, and extrapolating this little changes the height by a
// negligible fraction of the triangle's height range.
constexpr double kInsideEps = 1e-6;

// Marks a sample no triangle contains (yet) in the per-sample error array; errors are >= 0.
constexpr float kNotCovered = -1.0f;

struct MeshPoint {
    double x, z; // metres on the ground
    double y;    // metres, scaled by ErrorOptions::verticalScale
};

// Twice the signed area of triangle (u, v, p) on the ground plane (x, z).
double edgeFunction(const MeshPoint& u, const MeshPoint& v, double px, double pz) {
    return (v.x - u.x) * (pz - u.z) - (v.z - u.z) * (px - u.x);
}

// Samples are at float-rounded positions, within 2^-24 * 2^21 = 0.125 spacings of their exact
// ones (kMaxTiledFieldSide); a candidate range widened by this much (in spacings) never misses one.
constexpr double kRoundingSlack = 0.25;

// The evaluated samples along one axis whose positions may lie in [lo, hi] metres, given
// `perMetre` = 1 / the metres between them and `count` of them: [first, last], empty when
// first > last. The exact test decides about the candidates.
struct IndexRange {
    int32_t first, last;
};
IndexRange indexRange(double lo, double hi, double perMetre, int32_t count) {
    const double u0 = lo * perMetre - kRoundingSlack, u1 = hi * perMetre + kRoundingSlack;
    if (!(u0 <= u1) || u1 < 0.0 || u0 > double(count - 1)) return {1, 0};
    // Clamped before converting, so the conversions stay in range; int32_t() floors u >= 0.
    int32_t first = 0;
    if (u0 > 0.0) {
        first = int32_t(u0);
        if (double(first) < u0) ++first; // ceil
    }
    const int32_t last = u1 < double(count - 1) ? int32_t(u1) : count - 1;
    return {first, last};
}

} // namespace

ErrorStats evaluateMeshError(const Heightfield& field, const float* positions, size_t vertexCount,
                             size_t strideFloats, const uint32_t* indices, size_t indexCount,
                             const ErrorOptions& options) {
    ErrorStats stats;
    if (!(options.verticalScale > 0.0f) || !std::isfinite(options.verticalScale)) {
        stats.error = "verticalScale must be finite and > 0";
        return stats;
    }
    if (options.sampleStride < 1) {
        stats.error = "sampleStride must be >= 1";
        return stats;
    }
    if (strideFloats < 3) {
        stats.error = "a vertex needs at least 3 floats (x, y, z)";
        return stats;
    }
    if (indexCount % 3 != 0) {
        stats.error = "the index count is not a multiple of 3";
        return stats;
    }
    if (indexCount > 0 && (!indices || !positions)) {
        stats.error = "indices or positions are missing";
        return stats;
    }
    for (size_t k = 0; k < indexCount; ++k) {
        if (indices[k] >= vertexCount) {
            stats.error = "an index is past the last vertex";
            return stats;
        }
    }

    // The evaluated samples form a grid of cols x rows, every `step`-th column and row.
    const int32_t step = options.sampleStride;
    const int32_t cols = (field.width() - 1) / step + 1;
    const int32_t rows = (field.height() - 1) / step + 1;
    const double dx = double(step) * field.scale().spacingX; // metres between evaluated columns
    const double dz = double(step) * field.scale().spacingY; // metres between evaluated rows
    const double columnsPerMetre = 1.0 / dx, rowsPerMetre = 1.0 / dz;
    // Sample positions rounded to float as a vertex placed on the sample stores them,
    // float(j * spacingX), so such a vertex coincides exactly with its sample.
    std::vector<double> xs(static_cast<size_t>(cols)), zs(static_cast<size_t>(rows));
    for (int32_t a = 0; a < cols; ++a) xs[size_t(a)] = float(double(a * step) * field.scale().spacingX);
    for (int32_t b = 0; b < rows; ++b) zs[size_t(b)] = float(double(b * step) * field.scale().spacingY);

    // Error per evaluated sample: it marks which samples are covered, keeps one value per
    // sample for the mean and the percentile, and is the buffer the percentile is taken in.
    // Counted in 64 bits: size_t is 32 bits under WebAssembly, and a world field has 8e11 samples.
    const uint64_t evaluated = uint64_t(cols) * uint64_t(rows);
    std::unique_ptr<float[]> errors;
    if (evaluated <= uint64_t(SIZE_MAX / sizeof(float))) errors.reset(new (std::nothrow) float[size_t(evaluated)]);
    const size_t sampleCount = size_t(evaluated);
    if (!errors) {
        stats.error = "out of memory for the per-sample errors: use a larger sampleStride";
        return stats;
    }
    std::fill(errors.get(), errors.get() + sampleCount, kNotCovered);

    const float verticalScale = options.verticalScale;
    const double toFieldMetres = 1.0 / double(verticalScale);
    for (size_t t = 0; t < indexCount; t += 3) {
        MeshPoint p[3];
        for (int k = 0; k < 3; ++k) {
            const float* v = positions + size_t(indices[t + size_t(k)]) * strideFloats;
            p[k] = {v[0], v[2], v[1]};
        }
        // One test for all nine coordinates: a NaN or an infinity makes the sum non-finite.
        if (!std::isfinite(p[0].x + p[0].y + p[0].z + p[1].x + p[1].y + p[1].z + p[2].x + p[2].y + p[2].z))
            continue;
        // Any winding: make the edge functions of inside points positive.
        double area2 = edgeFunction(p[0], p[1], p[2].x, p[2].z);
        if (area2 < 0.0) {
            std::swap(p[1], p[2]);
            area2 = -area2;
        }
        const double minX = std::min({p[0].x, p[1].x, p[2].x});
        const double maxX = std::max({p[0].x, p[1].x, p[2].x});
        const double minZ = std::min({p[0].z, p[1].z, p[2].z});
        const double maxZ = std::max({p[0].z, p[1].z, p[2].z});
        // Degenerate: zero area up to the rounding of the products in edgeFunction.
        const double extent = std::max(maxX - minX, maxZ - minZ);
        if (!(area2 > 1e-12 * extent * extent)) continue;
        const double tolerance = kInsideEps * area2; // in edge-function units
        // Edge k runs from p[k] to p[k+1]; 1 / its z extent, for the row spans below.
        double inverseDz[3];
        for (int k = 0; k < 3; ++k) {
            const double dzEdge = p[(k + 1) % 3].z - p[k].z;
            inverseDz[k] = dzEdge != 0.0 ? 1.0 / dzEdge : 0.0;
        }

        const IndexRange rowRange = indexRange(minZ, maxZ, rowsPerMetre, rows);
        for (int32_t b = rowRange.first; b <= rowRange.last; ++b) {
            const double z = zs[size_t(b)];
            // Along this row each edge function is linear in x: intersect the three x ranges
            // where it is >= -tolerance, so thin or diagonal triangles cost no more than
            // the samples they hold.
            double xLo = minX, xHi = maxX;
            for (int k = 0; k < 3; ++k) {
                const MeshPoint& u = p[k];
                const MeshPoint& v = p[(k + 1) % 3];
                // edge(x) = across - (v.z - u.z) * (x - u.x)
                const double across = (v.x - u.x) * (z - u.z);
                const double bound = u.x + (across + tolerance) * inverseDz[k];
                if (v.z > u.z) xHi = std::min(xHi, bound);
                else if (v.z < u.z) xLo = std::max(xLo, bound);
                else if (across < -tolerance) xHi = -INFINITY; // the row is outside this edge
            }
            const int32_t row = b * step;
            const bool shifted = options.shiftedOddRows && (row & 1) != 0;
            const double shift = shifted ? 0.5 * field.scale().spacingX : 0.0;
            const IndexRange colRange = indexRange(xLo - shift, xHi - shift, columnsPerMetre, cols);
            for (int32_t a = colRange.first; a <= colRange.last; ++a) {
                // As the embedding stores the vertex on this sample (embedding.cpp).
                const double x = shifted ? double(float((double(a * step) + 0.5) * field.scale().spacingX)) : xs[size_t(a)];
                const double e0 = edgeFunction(p[1], p[2], x, z);
                const double e1 = edgeFunction(p[2], p[0], x, z);
                const double e2 = edgeFunction(p[0], p[1], x, z);
                if (e0 < -tolerance || e1 < -tolerance || e2 < -tolerance) continue;
                // Barycentric weights relative to vertex 0: on a vertex they are exactly 0 or
                // 1, so the mesh height there is exactly the vertex height.
                const double sum = e0 + e1 + e2;
                const double w1 = e1 / sum, w2 = e2 / sum;
                const double meshY = p[0].y + w1 * (p[1].y - p[0].y) + w2 * (p[2].y - p[0].y);
                // The sample's height as a mesh vertex on it stores it (a float product).
                const float height = shifted ? 0.5f * (field.heightClamped(a * step, row) + field.heightClamped(a * step + 1, row))
                                             : field.heightAt(a * step, row);
                const float sampleY = height * verticalScale;
                const float error = float(std::abs(meshY - double(sampleY)) * toFieldMetres);
                float& slot = errors[size_t(b) * size_t(cols) + size_t(a)];
                slot = std::max(slot, error); // a sample on a shared edge keeps the larger error
            }
        }
    }

    // One pass over the samples: counts, mean and the worst sample, while packing the covered
    // samples' errors to the front of the array for the percentile.
    double errorSum = 0.0;
    float worst = -1.0f;
    size_t covered = 0;
    for (int32_t b = 0; b < rows; ++b) {
        for (int32_t a = 0; a < cols; ++a) {
            const float e = errors[size_t(b) * size_t(cols) + size_t(a)];
            if (e == kNotCovered) continue;
            if (e > worst) {
                worst = e;
                stats.worstColumn = a * step;
                stats.worstRow = b * step;
            }
            errorSum += e;
            errors[covered++] = e; // covered <= the index read, so nothing unread is overwritten
        }
    }
    stats.evaluated = int64_t(covered);
    stats.uncovered = int64_t(sampleCount - covered);
    if (covered == 0) return stats;
    stats.maxError = worst;
    stats.meanError = errorSum / double(covered);
    // Nearest rank: the smallest error that at least 99% of the evaluated samples do not exceed.
    const size_t rank = (covered * 99 + 99) / 100 - 1;
    std::nth_element(errors.get(), errors.get() + rank, errors.get() + covered);
    stats.p99Error = errors[rank];
    return stats;
}

} // namespace hexlod
