// The budget of one update (§6: the refinement is interruptible, and each update resumes where
// the last one stopped): its time and operations, and the automatic tau that keeps the update
// within the time budget and the mesh under the triangle cap. See refiner.h.
#include "lod/refiner.h"

#include <algorithm>

namespace hexlod {

bool Refiner::outOfBudget(double share) {
    if (settings_.maxOperations > 0 && operations_ >= std::max(1, int32_t(double(settings_.maxOperations) * share))) return true;
    // Reading the clock costs more than testing a cell: look at it every 32 visits.
    if (settings_.budgetMs > 0.0 && (visits_ & 31) == 0) {
        const double ms = frameClockMs() - startMs_;
        if (ms >= settings_.budgetMs * share) return true;
    }
    return false;
}

void Refiner::adaptTau() {
    if (settings_.viewIndependent || !settings_.autoTau) {
        currentTau_ = settings_.tau;
        return;
    }
    const bool overCap = settings_.maxTriangles > 0 && mesh_->triangleCount() >= settings_.maxTriangles;
    const bool overTime = settings_.budgetMs > 0.0 && last_.milliseconds >= settings_.budgetMs && !last_.converged;
    if (overCap || overTime) currentTau_ = std::min(currentTau_ * 1.1, settings_.tau * 64.0);
    else if (last_.converged) currentTau_ = std::max(currentTau_ / 1.05, settings_.tau);
}

} // namespace hexlod
