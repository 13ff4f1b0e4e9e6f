#include "embedding.h"

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

} // namespace hexlod
