// The refiner over a field whose samples arrive by tiles (field/sample_tiles.h): when heights
// change under cells, their cached refinement data (§5.1) is measured again. See refiner.h.
#include "lod/refiner.h"

#include <algorithm>
#include <cmath>

namespace hexlod {

void Refiner::heightsChanged(const SampleRect& rect, bool rangeGrew) {
    if (!mesh_ || rect.empty()) return;
    pyramid_.update(*field_, rect);
    const int32_t cells = mesh_->cellCapacity();
    if (rangeGrew) {
        cache_.setHeightRange(field_->minHeight(), field_->maxHeight());
        for (int32_t c = 0; c < cells; ++c) cache_.invalidate(c);
        restart();
        return;
    }
    const double sx = field_->scale().spacingX, sy = field_->scale().spacingY;
    const int32_t block = pyramid_.block();
    for (int32_t c = 0; c < cells; ++c) {
        if (!mesh_->isLive(c)) continue;
        // The parent's footprint holds the cell's; a pyramid query (cell_bounds.cpp) reads
        // whole blocks of up to a quarter of the footprint a side, beyond it.
        const Footprint f = footprintOf(*field_, mesh_->embedding(), parentShapeOfCell(*mesh_, c));
        const int32_t j0 = int32_t(std::floor(f.x0 / sx)), j1 = int32_t(std::ceil(f.x1 / sx));
        const int32_t i0 = int32_t(std::floor(f.z0 / sy)), i1 = int32_t(std::ceil(f.z1 / sy));
        const int32_t reach = std::max(j1 - j0, i1 - i0) / 2 + 2 * block;
        if (!rect.intersects({j0 - reach, i0 - reach, j1 + reach, i1 + reach})) continue;
        cache_.invalidate(c);
        starved_[size_t(c)] = 0.0f;
        makeDue(c);
    }
}

} // namespace hexlod
