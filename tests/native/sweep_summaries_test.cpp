// The summaries the refiner's sweep passes over groups of records: a group is
// passed over only while none of its records is due under its renewed form
// (CameraOdometers::renewed, itself a bound: camera_odometers_test.cpp checks the verdicts),
// whatever the camera does, records set or made due since, and long pauses included.
#include "lod/sweep_summaries.h"

#include <gtest/gtest.h>

#include "views.h"

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

using namespace hexlod;
using test::viewAt;

namespace {

struct Record {
    uint32_t stamp = 0;
    Odometer odometer = Odometer::Travel;
    float dist = 0.0f, rho = -1.0f;
};

// What the summary promises for a record: its renewed form when the summary was made, or the
// record itself when it was set since.
struct Promise {
    uint32_t stamp = 0;
    float dist = 0.0f, rho = -1.0f;
};

struct Tally {
    int64_t passedOver = 0, read = 0;
};

// A random camera (moves, turns, holds still for long stretches) over random records. speed:
// metres a frame; turn: radians a frame.
Tally fly(uint32_t seed, int32_t frames, double speed, double turn) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto randomRecord = [&](uint32_t stamp, Record& r) {
        r.stamp = stamp;
        r.odometer = Odometer(int32_t(unit(rng) * 5.999));
        r.dist = float(100.0 + 5000.0 * unit(rng));
        const double kind = unit(rng);
        r.rho = kind < 0.05 ? std::numeric_limits<float>::max() : CameraOdometers::storedMargin(std::exp(8.0 * unit(rng)));
    };
    constexpr int32_t kRecords = 20 * SweepSummaries::kGroup + 17; // a last group of 17
    std::vector<Record> records(kRecords);
    std::vector<Promise> promises(kRecords);
    SweepSummaries summaries;
    summaries.resize(records.size(), records.size());
    SweepSummaries::Maker maker;
    CameraOdometers odometers;
    glm::dvec3 eye(0.0);
    double yaw = 0.0, pitch = 0.2;
    View view = viewAt(eye, yaw, pitch);
    Tally result;
    bool still = false;
    for (int32_t frame = 0; frame < frames; ++frame) {
        if (unit(rng) < 0.01) still = !still; // stretches of a hundred frames or so
        if (!still) {
            eye += glm::dvec3(std::sin(yaw), 0.1 * (unit(rng) - 0.5), -std::cos(yaw)) * (speed * unit(rng));
            yaw += turn * (unit(rng) - 0.5);
            pitch += 0.2 * turn * (unit(rng) - 0.5);
        }
        const View next = viewAt(eye, yaw, pitch);
        odometers.move(view, next);
        view = next;
        EXPECT_FALSE(odometers.beginUpdate());
        // A change makes a few records due.
        for (int32_t k = 0; k < 3; ++k) {
            const int32_t i = int32_t(unit(rng) * (kRecords - 1));
            records[size_t(i)].rho = -1.0f;
            summaries.madeDue(i);
        }
        for (int32_t g = 0; g < summaries.groups(); ++g) {
            const int32_t first = g * SweepSummaries::kGroup, end = std::min(kRecords, first + SweepSummaries::kGroup);
            if (summaries.canSkip(g, odometers)) {
                ++result.passedOver;
                for (int32_t i = first; i < end; ++i) {
                    const Promise& p = promises[size_t(i)];
                    if (odometers.usedUp(p.stamp, records[size_t(i)].odometer, p.dist, p.rho)) {
                        ADD_FAILURE() << "group " << g << " passed over with record " << i << " due, frame " << frame;
                        return result;
                    }
                }
                continue;
            }
            ++result.read;
            maker.start();
            std::vector<int32_t> due;
            for (int32_t i = first; i < end; ++i) {
                Record& r = records[size_t(i)];
                const CameraOdometers::Reading reading = odometers.read(r.stamp, r.odometer, r.dist);
                if (reading.used > r.rho) {
                    due.push_back(i);
                    continue;
                }
                maker.add(r.odometer, r.rho, r.dist, odometers.age(r.stamp), reading);
                const CameraOdometers::Renewed renewed = odometers.renewed(r.stamp, r.odometer, r.dist, r.rho);
                promises[size_t(i)] = {odometers.stamp(), renewed.dist, renewed.rho};
                if (odometers.age(r.stamp) >= CameraOdometers::kHistory / 2) r = {odometers.stamp(), r.odometer, renewed.dist, renewed.rho};
            }
            maker.finish(summaries, g, odometers);
            for (int32_t i : due) { // tested: a new record
                Record& r = records[size_t(i)];
                randomRecord(odometers.stamp(), r);
                summaries.set(i, r.odometer, r.dist, r.rho);
                promises[size_t(i)] = {r.stamp, r.dist, r.rho};
            }
        }
    }
    return result;
}

} // namespace

TEST(SweepSummaries, AGroupIsPassedOverOnlyWhileNoneOfItsRecordsIsDue) {
    const int32_t frames = 3 * int32_t(CameraOdometers::kHistory); // pauses longer than the history come up
    Tally total;
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        const double speed = seed % 3 == 0 ? 2.0 : seed % 3 == 1 ? 20.0 : 200.0;
        const double turn = seed % 2 == 0 ? 0.001 : 0.03;
        const Tally r = fly(seed, frames, speed, turn);
        total.passedOver += r.passedOver, total.read += r.read;
    }
    std::printf("sweep summaries: %lld groups passed over, %lld read\n", (long long)total.passedOver, (long long)total.read);
    EXPECT_GT(total.passedOver, total.read / 4) << "the summaries should let the sweep pass over groups";
}

TEST(SweepSummaries, AGroupMadeDueGrownRenumberedOrOldIsRead) {
    CameraOdometers odometers;
    odometers.beginUpdate();
    SweepSummaries summaries;
    summaries.resize(100, 100);
    ASSERT_EQ(summaries.groups(), 2);
    EXPECT_FALSE(summaries.canSkip(0, odometers)) << "a new group has no summary";
    SweepSummaries::Maker maker;
    auto make = [&](int32_t g) {
        maker.start();
        maker.add(Odometer::Travel, 500.0f, 1000.0f, 0, odometers.read(odometers.stamp(), Odometer::Travel, 1000.0f));
        maker.finish(summaries, g, odometers);
    };
    make(0), make(1);
    EXPECT_TRUE(summaries.canSkip(0, odometers) && summaries.canSkip(1, odometers)) << "the camera has not moved";
    summaries.resize(130, 130); // records 100.. join group 1 and fill group 2
    EXPECT_TRUE(summaries.canSkip(0, odometers));
    EXPECT_FALSE(summaries.canSkip(1, odometers)) << "grown";
    EXPECT_FALSE(summaries.canSkip(2, odometers)) << "new";
    make(1), make(2);
    summaries.madeDue(70);
    EXPECT_TRUE(summaries.canSkip(0, odometers));
    EXPECT_FALSE(summaries.canSkip(1, odometers)) << "made due";
    summaries.readAll();
    EXPECT_FALSE(summaries.canSkip(0, odometers)) << "all read";
    make(0);
    // A still camera uses no margin, but a record old enough to be renewed has its group read
    // (and a summary older than the odometers' history could not be read back).
    const View still = {};
    for (uint32_t k = 1; k < CameraOdometers::kHistory / 2; ++k) {
        odometers.move(still, still);
        odometers.beginUpdate();
    }
    EXPECT_TRUE(summaries.canSkip(0, odometers));
    odometers.move(still, still);
    odometers.beginUpdate();
    EXPECT_FALSE(summaries.canSkip(0, odometers)) << "a record to renew";
}
