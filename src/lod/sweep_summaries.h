// Summaries of the refiner's test records (refiner.h) in groups of kGroup, so that its sweep
// can pass over a group none of whose records can be due without reading them: on a large
// mesh a few in a thousand records are due in a frame, and reading the others was most of an
// update.
//
// A group's summary is made when the sweep reads the group: every record that is not due is
// renewed in thought (CameraOdometers::renewed: what is left of its margin now, for a centre
// as far as the eye can have got from it since), and the summary keeps, per odometer, the
// least margin left, and the largest distance. While the camera has not used up that least
// margin since, for that distance, no record of the group is due under its renewed form,
// which is a bound as the record itself is (renewing is). A record set since (a test) only
// lowers the margin or raises the distance; a record made due (rho < 0) or a group that grew
// has the group read again; so does a record old enough to be renewed.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "lod/camera_odometers.h"
#include "lod/float_rounding.h"
#include "mesh/pool_growth.h"

namespace hexlod {

class SweepSummaries {
public:
    static constexpr int32_t kGroup = 64;
    // One slot per odometer, but travel and steady share one, read as steady (which charges
    // at least what travel does): a summary stays 32 bytes.
    static constexpr int32_t kSlots = 5;
    static int32_t slotOf(Odometer odometer) { return odometer == Odometer::Steady ? 0 : int32_t(odometer); }
    static Odometer odometerOf(int32_t slot) { return slot == 0 ? Odometer::Steady : Odometer(slot); }

    static int32_t groupOf(int32_t record) { return record / kGroup; }
    int32_t groups() const { return int32_t(summaries_.size()); }

    /// Room for `records` records, pool-like (pool_growth.h); groups that are new or that new
    /// records joined are read at the next sweep.
    void resize(size_t records, size_t poolCapacity) {
        const size_t before = summaries_.size();
        const size_t count = (records + kGroup - 1) / kGroup;
        reserveLikePool(summaries_, count, (poolCapacity + kGroup - 1) / kGroup);
        summaries_.resize(count);
        for (size_t g = before > 0 ? before - 1 : 0; g < count; ++g) summaries_[g].reach = -1.0f;
    }
    void release() { releasePool(summaries_); }
    /// Every group is read at the next sweep (every record due, or records renumbered).
    void readAll() {
        for (Summary& s : summaries_) s.reach = -1.0f;
    }
    /// The record was made due: its group is read at the next sweep.
    void madeDue(int32_t record) { summaries_[size_t(groupOf(record))].reach = -1.0f; }
    /// A record was set (tested now): the summary still bounds it. rho and dist as the record
    /// keeps them.
    void set(int32_t record, Odometer odometer, float dist, float rho) {
        Summary& s = summaries_[size_t(groupOf(record))];
        if (s.reach < 0.0f) return; // read anyway
        float& slack = s.slack[slotOf(odometer)];
        slack = std::min(slack, rho);
        s.reach = std::max(s.reach, dist);
    }

    /// Whether the sweep may pass over the group: made, none of its records old enough to
    /// renew, and none due under the summary.
    bool canSkip(int32_t group, const CameraOdometers& odometers) const {
        const Summary& s = summaries_[size_t(group)];
        if (s.reach < 0.0f || odometers.age(s.made) + s.oldestAge >= CameraOdometers::kHistory / 2) return false;
        for (int32_t o = 0; o < kSlots; ++o)
            if (s.slack[o] < std::numeric_limits<float>::max() && odometers.usedUp(s.made, odometerOf(o), s.reach, s.slack[o])) return false;
        return true;
    }

    /// Makes a group's summary while the sweep reads it: add() for every record that is not
    /// due (after the check, before a renewal), then finish().
    class Maker {
    public:
        void start() {
            std::fill(std::begin(left_), std::end(left_), std::numeric_limits<float>::infinity());
            reach_ = 0.0f;
            oldestAge_ = 0;
        }
        /// A record (rho, dist, stamp `age` updates ago) and its reading (CameraOdometers::read),
        /// whose used figure is not above rho.
        void add(Odometer odometer, float rho, float dist, uint32_t age, CameraOdometers::Reading reading) {
            // What is left, and how far the centre can be now (CameraOdometers::renewed), in
            // floats: the reading is within three roundings (each 2^-24) of the exact figure, a
            // relative 2^-21 more covers them; finish() covers the rounding of these two.
            float& left = left_[slotOf(odometer)];
            left = std::min(left, rho - reading.used * (1.0f + 0x1p-21f));
            reach_ = std::max(reach_, dist + reading.travel);
            oldestAge_ = std::max(oldestAge_, age);
        }
        void finish(SweepSummaries& into, int32_t group, const CameraOdometers& odometers) const {
            Summary& s = into.summaries_[size_t(group)];
            s.made = odometers.stamp();
            s.oldestAge = oldestAge_;
            for (int32_t o = 0; o < kSlots; ++o) {
                // A margin no camera uses up (a parked record, a verdict forever) stays so.
                // storedMargin takes a relative 2^-20 off, more than the subtraction's rounding.
                const float left = left_[o];
                s.slack[o] = left > 1e37f ? std::numeric_limits<float>::max() : CameraOdometers::storedMargin(std::max(0.0, double(left)));
            }
            s.reach = roundedUp(double(reach_) * (1.0 + 0x1p-22)); // the sum's rounding
        }

    private:
        float left_[kSlots];
        float reach_;
        uint32_t oldestAge_;
    };

    size_t memoryBytes() const { return summaries_.capacity() * sizeof(Summary); }
    static constexpr double bytesPerRecord() { return double(sizeof(Summary)) / kGroup; }

private:
    struct Summary {
        uint32_t made = 0;   // the update the summary was made in
        uint32_t oldestAge = 0; // the age of its oldest record then (updates)
        float reach = -1.0f; // the largest distance of a centre (renewed); < 0: read the group
        float slack[kSlots] = {}; // per slot (slotOf), the least margin left (renewed); the largest float: none
    };
    static_assert(sizeof(Summary) == 32, "32 bytes a group");
    std::vector<Summary> summaries_;
};

} // namespace hexlod
