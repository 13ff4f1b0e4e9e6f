// The achieved screen error of the current mesh, for the viewer's HUD: what the refiner's
// bound (paper §5, view_criteria.h) says of the cells now drawn, for the current camera. Once
// converged it is at most tau (the refiner's promise); while refining, or with a triangle cap,
// it shows how far the mesh is from it. Kept out of refiner.cpp: it reads the per-cell cache
// (§5.1) and changes nothing.
#include "lod/refiner.h"

#include <algorithm>
#include <cmath>

namespace hexlod {

double Refiner::achievedErrorPixels() const {
    if (settings_.viewIndependent || !mesh_) return -1.0;
    double worst = 0.0;
    const int32_t cells = std::min(mesh_->cellCapacity(), int32_t(cache_.size()));
    for (int32_t c = 0; c < cells; ++c) {
        // A cell not tested since it was made has no bound yet; the next update computes it.
        if (!mesh_->isLive(c) || !cache_.hasOwn(c)) continue;
        const CellError own = cache_.own(c);
        glm::dvec3 center;
        double radius;
        const Footprint f = footprintOf(*field_, mesh_->embedding(), shapeOfCell(*mesh_, c));
        boundingSphere(f, own, settings_.verticalScale, center, radius);
        const double error = double(own.error) * settings_.verticalScale;
        if (!settings_.earth.flat()) {
            // On the curved Earth, as judgeCell (cell_verdict.cpp): the image's bound.
            CurvedCell curved = curvedCellOf(settings_.earth, f, own, settings_.verticalScale);
            // A cell of one sample's step in the exact embedding has every sample under it as
            // a vertex, drawn where it belongs: its chords pass over no sample.
            if (mesh_->embedding() == Embedding::Exact && mesh_->cellStep(c) == 1) curved.sag = curved.drift = 0.0;
            if (settings_.culling && outsideFrustum(view_, curved.center, curved.radius)) continue;
            if (settings_.backfaceCulling && curvedBackFaces(view_, settings_.earth, curved, cache_.ownSlopes(c), settings_.verticalScale).backFacing) continue;
            worst = std::max(worst, projectedErrorPixels(view_, curved, error, view_.nearPlane));
            continue;
        }
        // Cells that cannot be seen do not count: outside the (unwidened) frustum, or back-facing.
        if (settings_.culling && outsideFrustum(view_, center, radius)) continue;
        if (settings_.backfaceCulling && backFaces(view_, center, radius, cache_.ownSlopes(c), settings_.verticalScale).backFacing)
            continue;
        worst = std::max(worst, projectedErrorPixels(view_, center, radius, error));
    }
    return worst;
}

} // namespace hexlod
