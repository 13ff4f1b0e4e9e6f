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
    const int32_t block = pyramid_.block();
    for (int32_t c = 0; c < cells; ++c) {
        if (!mesh_->isLive(c)) continue;
        // The parent's footprint holds the cell's; a pyramid query (cell_bounds.cpp) reads
        // whole blocks of up to a quarter of the footprint a side, beyond it.
        const Footprint f = footprintOf(*field_, mesh_->embedding(), parentShapeOfCell(*mesh_, c));
        const SampleRect r = samplesUnder(*field_, f);
        const int32_t reach = std::max(r.j1 - r.j0, r.i1 - r.i0) / 2 + 2 * block;
        if (!rect.intersects({r.j0 - reach, r.i0 - reach, r.j1 + reach, r.i1 + reach})) continue;
        cache_.invalidate(c);
        starved_[size_t(c)] = 0.0f;
        makeDue(c);
    }
}

} // namespace hexlod
