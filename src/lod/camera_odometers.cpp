// The camera's odometers (camera_odometers.h).
#include "lod/camera_odometers.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hexlod {

void CameraOdometers::move(const View& from, const View& to) {
    const glm::dvec3 step = to.eye - from.eye;
    stepAlong_[0] += glm::length(step);
    const glm::dvec3 dr = to.right - from.right, du = to.up - from.up, df = to.forward - from.forward;
    stepTurn_ += std::sqrt(glm::dot(dr, dr) + glm::dot(du, du) + glm::dot(df, df));
    // The world's up vector in view coordinates is (right.y, up.y, forward.y).
    stepTilt_ += glm::length(glm::dvec3(dr.y, du.y, df.y));
    // In the new view's coordinates a fixed point moves by -v, besides the turn's share. A side
    // plane's slack (judgeCell, cell_verdict.cpp: e.g. (tanX z - x) / sqrt(1 + tanX^2) for the right plane)
    // has a unit gradient n; the point moves inwards across it by -n.v, never more than |v|.
    const double x = glm::dot(step, to.right), y = glm::dot(step, to.up), z = glm::dot(step, to.forward);
    const double sx = std::sqrt(1.0 + to.tanHalfX * to.tanHalfX), sy = std::sqrt(1.0 + to.tanHalfY * to.tanHalfY);
    const double inwards[4] = {(x - to.tanHalfX * z) / sx, (-x - to.tanHalfX * z) / sx,
                               (y - to.tanHalfY * z) / sy, (-y - to.tanHalfY * z) / sy};
    for (int32_t p = 0; p < 4; ++p) stepAlong_[1 + p] += std::max(0.0, inwards[p]);
}

bool CameraOdometers::beginUpdate() {
    // The camera's step since the last update counts for every update before this one; the
    // sums are rounded up, so what a record is charged never falls short.
    const int32_t steady = int32_t(Odometer::Steady);
    for (Spent& since : spent_) {
        for (int32_t k = 0; k < steady; ++k) {
            since.along[k] = roundedUp(double(since.along[k]) + stepAlong_[k]);
            since.turn[k] = roundedUp(double(since.turn[k]) + stepTurn_);
        }
        since.along[steady] = roundedUp(double(since.along[steady]) + stepAlong_[0]);
        since.turn[steady] = roundedUp(double(since.turn[steady]) + stepTurn_ + kTiltWeight * stepTilt_);
    }
    // A tilt well below what a person pitching the view makes (a milliradian a frame and more)
    // does not end a quiet stretch: the page's camera keeps its eye and target in 32-bit floats,
    // so a level flight still tilts by up to about 3e-7 a frame. It is charged anyway.
    quietUpdates_ = stepTilt_ > kQuietTilt ? 0u : quietUpdates_ + 1u;
    for (double& a : stepAlong_) a = 0.0;
    stepTurn_ = stepTilt_ = 0.0;
    stamp_ = (stamp_ + 1u) & kStampMask;
    spent_[stamp_ % kHistory] = Spent{};
    return stamp_ == 0u;
}

} // namespace hexlod
