// The lattice embedding of paper §4.7; see embedding.h.
#include "mesh/embedding.h"

#include <algorithm>
#include <cstdlib>

namespace hexlod {

glm::vec3 embedLatticePoint(const Heightfield& field, Embedding embedding, LatticePoint p) {
    const HeightfieldScale& scale = field.scale();
    const int32_t j = sampleColumn(p);
    const bool oddRow = (p.r & 1) != 0;
    const float z = float(double(p.r) * scale.spacingY);
    if (embedding == Embedding::Exact || !oddRow) {
        return {float(double(j) * scale.spacingX), field.heightClamped(j, p.r), z};
    }
    // Shifted odd row: half a sample east, height interpolated between its two samples.
    const float h = 0.5f * (field.heightClamped(j, p.r) + field.heightClamped(j + 1, p.r));
    return {float((double(j) + 0.5) * scale.spacingX), h, z};
}

bool latticePointMissing(const Heightfield& field, Embedding embedding, LatticePoint p) {
    const int32_t last = field.width() - 1;
    const int32_t j = std::clamp(sampleColumn(p), 0, last), i = std::clamp(p.r, 0, field.height() - 1);
    if (field.sampleMissing(j, i)) return true;
    return embedding == Embedding::Shifted && (p.r & 1) != 0 && field.sampleMissing(std::min(j + 1, last), i);
}

namespace {

// Twice the ground-plane area of a triangle in sample units (x doubled to stay integer).
int64_t groundArea2(Embedding embedding, LatticePoint a, LatticePoint b, LatticePoint c) {
    auto x2 = [&](LatticePoint p) { return embedding == Embedding::Exact ? 2 * int64_t(sampleColumn(p)) : 2 * int64_t(p.q) + p.r; };
    return std::abs((x2(b) - x2(a)) * int64_t(c.r - a.r) - (x2(c) - x2(a)) * int64_t(b.r - a.r));
}

} // namespace

bool semiFanFromSecondCorner(Embedding embedding, LatticePoint a, LatticePoint b, LatticePoint c, LatticePoint d) {
    const int64_t fromA = std::min(groundArea2(embedding, a, b, c), groundArea2(embedding, a, c, d));
    const int64_t fromB = std::min(groundArea2(embedding, b, c, d), groundArea2(embedding, b, d, a));
    return fromB > fromA;
}

} // namespace hexlod
