// The camera's odometers, which deferred re-testing measures its margins with (refiner.h),
// and their readings at the last updates.
//
// A margin says how far a cell's centre may move in view coordinates before a verdict can
// change. Most verdicts hold against movement in any direction, and are measured by the
// distance the eye travelled. A cell culled by a side plane of the frustum stays culled until
// its centre moves back across that plane: only the component of the eye's movement that
// brings cells inside that plane counts, and one odometer per side plane adds it up. A camera
// flying forward moves every cell beside it further out, so the band of culled cells along
// the sides of the view is not re-tested at every step.
//
// The view's turning moves a centre at distance D by at most turn * D (turn: the Frobenius
// norm of the change of the view basis), whatever the odometer; it is added to each.
//
// Turning also tilts the world's up vector in view coordinates, which changes how large a
// vertical error looks on the screen (cell_verdict.h). A turn of the view basis bounds that
// tilt, so a margin m on the travel odometer allows a tilt of m / D. A camera that flies and
// yaws, as a flight does, tilts nothing, and leaving room for that tilt costs a quarter of the
// margins of far merge tests. So while the camera has not tilted for kQuietUpdates updates,
// verdicts are measured by the steady odometer instead: the travel, plus the tilt charged
// apart at kTiltWeight D, which allows a tilt of only m / (kTiltWeight D). When the camera
// pitches again those records come due (1 + kTiltWeight times as fast as on travel) and their
// re-tests go back to the travel odometer. (On the Grand Canyon at 50 m a frame, whose camera
// does not tilt: 727 cells tested a frame on travel alone, 608 with the steady odometer at a
// weight of 8, 601 at 16; charging every record for the tilt at a weight of 4 instead, 611,
// but a camera looking up and down then tests twice as many cells.)

// Records keep the update they were tested in (a stamp); what the camera did since each of
// the last kHistory updates is kept here, so a record needs no copy of the odometers. An
// older record is due; the refiner's sweep renews a record before that (Refiner::renew).
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include "lod/float_rounding.h"
#include "lod/view_criteria.h"

namespace hexlod {

/// What a margin is measured by. The planes in the order of judgeCell's slacks (cell_verdict.cpp). Steady
/// charges at least what each of the others does.
enum class Odometer : uint8_t { Travel = 0, RightPlane, LeftPlane, TopPlane, BottomPlane, Steady };

class CameraOdometers {
public:
    static constexpr uint32_t kHistory = 256;  // updates a record's stamp can be read back
    static constexpr uint32_t kStampBits = 29; // stamps wrap at 2^29 updates (about 100 days at 60 Hz)
    static constexpr int32_t kOdometers = 6;
    static constexpr double kTiltWeight = 8.0;
    static constexpr uint32_t kQuietUpdates = 8;
    static constexpr double kQuietTilt = 1e-5; // a tilt per update below this is no pitching

    /// The largest tilt of the world's up vector in view coordinates (the length of its change)
    /// that a margin on `odometer` allows for a centre at distance `dist` (see above).
    static double tiltAllowed(double margin, double dist, Odometer odometer) {
        return margin / ((odometer == Odometer::Steady ? kTiltWeight : 1.0) * dist);
    }
    /// What a verdict that is not a cull by a side plane is measured by in this update: steady
    /// while the camera has not tilted for kQuietUpdates updates.
    Odometer moving() const { return quietUpdates_ >= kQuietUpdates ? Odometer::Steady : Odometer::Travel; }

    /// The camera moved from one view to the next (same frustum shape).
    void move(const View& from, const View& to);
    /// Starts an update: its stamp, and what the camera did since each of the last kHistory
    /// updates. True when stamps wrapped (every record must then be due).
    bool beginUpdate();
    uint32_t stamp() const { return stamp_; }
    /// Updates since `stamp`.
    uint32_t age(uint32_t stamp) const { return (stamp_ - stamp) & kStampMask; }

    /// How much of a margin measured by `odometer` the camera has used since the update
    /// `stamp`, for a centre then at distance at most `dist`. Infinite for a stamp older than
    /// kHistory updates.
    double used(uint32_t stamp, Odometer odometer, float dist) const {
        if (age(stamp) >= kHistory) return std::numeric_limits<double>::infinity();
        const Spent& since = spent_[stamp % kHistory];
        return double(since.along[int32_t(odometer)]) + double(since.turn[int32_t(odometer)]) * (double(dist) + double(since.along[0]));
    }
    /// usedUp's figure (used() in floats), and the distance the eye travelled, since the
    /// update `stamp`: the sweep's reading of one record. Used infinite for a stamp older
    /// than kHistory.
    struct Reading {
        float used, travel;
    };
    Reading read(uint32_t stamp, Odometer odometer, float dist) const {
        const Spent& since = spent_[stamp % kHistory];
        const float used = since.along[int32_t(odometer)] + since.turn[int32_t(odometer)] * (dist + since.along[0]);
        return {age(stamp) >= kHistory ? std::numeric_limits<float>::infinity() : used, since.along[0]};
    }
    /// Whether a record's margin rho (kept as storedMargin gives it) is used up: used() in
    /// floats, the sweep's check of every record. A verdict holds for movement up to its
    /// margin, so a margin of 0 still holds while the camera stands still; rho < 0 is used up
    /// at once, as is a stamp older than kHistory.
    bool usedUp(uint32_t stamp, Odometer odometer, float dist, float rho) const { return read(stamp, odometer, dist).used > rho; }
    /// A margin as a record keeps it: rounded down, less the relative 2^-20 that covers the
    /// rounding of usedUp's three float operations (each within 2^-24 of the exact result).
    static float storedMargin(double margin) { return roundedDown(double(roundedDown(margin)) * (1.0 - 0x1p-20)); }
    /// A record not used up, re-stamped now (before its stamp gets too old to read back):
    /// what is left of its margin, for a centre as far as the eye can have got from it since.
    /// Still a bound: each later turn is charged at that distance, as it would have been, and
    /// what was used so far is charged once. rho: as storedMargin gives it.
    struct Renewed {
        float dist, rho;
    };
    Renewed renewed(uint32_t stamp, Odometer odometer, float dist, float rho) const {
        if (rho >= std::numeric_limits<float>::max()) return {dist, rho}; // a verdict no camera can change
        const double left = double(rho) - used(stamp, odometer, dist);
        return {roundedUp(double(dist) + double(spent_[stamp % kHistory].along[0])), storedMargin(left > 0.0 ? left : 0.0)};
    }

    static constexpr size_t memoryBytes() { return sizeof(Spent) * kHistory; }

private:
    static constexpr uint32_t kStampMask = (1u << kStampBits) - 1u;
    // What the camera did since one update, each figure rounded up, per odometer: along the
    // travel (along[0] and along[Steady]), or for side plane p the movement inwards across it
    // (along[1 + p]); turn what a record is charged per metre of distance, the summed turn
    // (plus kTiltWeight times the summed tilt for Steady).
    struct Spent {
        float along[kOdometers] = {};
        float turn[kOdometers] = {};
    };

    // Since the last update, not yet added to spent_.
    double stepAlong_[5] = {0, 0, 0, 0, 0}, stepTurn_ = 0.0, stepTilt_ = 0.0;
    uint32_t stamp_ = 0;
    uint32_t quietUpdates_ = 0; // updates since the camera last tilted
    std::array<Spent, kHistory> spent_{}; // by stamp % kHistory
};

} // namespace hexlod
