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

/// What a margin is measured by. The planes in the order of Refiner::judge's slacks.
enum class Odometer : uint8_t { Travel = 0, RightPlane, LeftPlane, TopPlane, BottomPlane };

class CameraOdometers {
public:
    static constexpr uint32_t kHistory = 256;  // updates a record's stamp can be read back
    static constexpr uint32_t kStampBits = 29; // stamps wrap at 2^29 updates (about 100 days at 60 Hz)

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
        return double(since.along[int32_t(odometer)]) + double(since.turn) * (double(dist) + double(since.along[0]));
    }
    /// usedUp's figure (used() in floats), and the distance the eye travelled, since the
    /// update `stamp`: the sweep's reading of one record. Used infinite for a stamp older
    /// than kHistory.
    struct Reading {
        float used, travel;
    };
    Reading read(uint32_t stamp, Odometer odometer, float dist) const {
        const Spent& since = spent_[stamp % kHistory];
        const float used = since.along[int32_t(odometer)] + since.turn * (dist + since.along[0]);
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
    // What the camera did since one update, each figure rounded up: along[0] the travel,
    // along[1 + p] the movement inwards across side plane p; turn the summed turn.
    struct Spent {
        float along[5] = {0, 0, 0, 0, 0};
        float turn = 0;
    };

    // Since the last update, not yet added to spent_.
    double stepAlong_[5] = {0, 0, 0, 0, 0}, stepTurn_ = 0.0;
    uint32_t stamp_ = 0;
    std::array<Spent, kHistory> spent_{}; // by stamp % kHistory
};

} // namespace hexlod
