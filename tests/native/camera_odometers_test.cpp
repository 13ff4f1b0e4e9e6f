// The camera's odometers (deferred re-testing): a margin measured on an odometer is
// a bound on the view-space movement of a centre and on the tilt of the world's up vector in
// view coordinates, also after a record is renewed, and a side plane's odometer leaves the
// cells beside a camera that flies forward alone.
#include "lod/camera_odometers.h"
#include "lod/sweep_summaries.h"

#include <gtest/gtest.h>

#include "views.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

using namespace hexlod;
using test::viewAt;

namespace {

// The slacks of the four side planes for a sphere, in Refiner::judge's order (negative: the
// sphere lies outside that plane).
void slacks(const View& v, const glm::dvec3& c, double radius, double out[4]) {
    const glm::dvec3 d = c - v.eye;
    const double x = glm::dot(d, v.right), y = glm::dot(d, v.up), z = glm::dot(d, v.forward);
    const double sx = std::sqrt(1.0 + v.tanHalfX * v.tanHalfX), sy = std::sqrt(1.0 + v.tanHalfY * v.tanHalfY);
    out[0] = (v.tanHalfX * z - x) / sx + radius, out[1] = (v.tanHalfX * z + x) / sx + radius;
    out[2] = (v.tanHalfY * z - y) / sy + radius, out[3] = (v.tanHalfY * z + y) / sy + radius;
}

struct Record {
    uint32_t stamp = 0;
    Odometer odometer = Odometer::Travel;
    float dist = 0.0f, rho = -1.0f;
    int32_t plane = -1; // culled by this plane; -1: inside every side plane
    float testedDist = 0.0f, rho0 = 0.0f; // the distance and margin it was tested with (a renewal keeps its odometer)
    glm::dvec3 up{0.0};      // the world's up vector in view coordinates when tested
};

glm::dvec3 upInView(const View& v) { return {v.right.y, v.up.y, v.forward.y}; }

struct Flight {
    double forward, sideways, climb, turn; // metres and radians a frame (random share added)
    int32_t pauseFrom = 0, pauseTo = 0;    // the camera holds still in these frames
    double nod = 0.0;                      // radians of pitch a frame, up or down (beside 0.2 turn)
    int32_t nodPeriod = 0;                 // > 0: nodding only in the last quarter of each period
};

// Flies `frames` frames, testing the spheres whose records are used up as the refiner does, and
// checks that every verdict still holds while its record is not. Returns the number of tests.
// planes false: every margin on the travel odometer, as before the side planes had their own.
// summaries: the records are swept in groups as Refiner::sweep does, passing over the groups
// whose summary (sweep_summaries.h) says none can be due; the verdicts of the records passed
// over must hold too. skipped: the groups passed over.
// steady: the tests whose verdicts went on the steady odometer (the camera had not tilted).
int64_t fly(const Flight& flight, int32_t frames, uint32_t seed, bool planes = true, bool summaries = false, int64_t* skipped = nullptr,
            int64_t* steady = nullptr) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<glm::dvec3> centres;
    std::vector<double> radii;
    for (int32_t i = 0; i < 3000; ++i) {
        centres.push_back({6000.0 * unit(rng), 300.0 * unit(rng) - 300.0, -6000.0 * (unit(rng) + 1.0) + 2000.0});
        radii.push_back(40.0 * (unit(rng) + 1.0));
    }
    std::vector<Record> records(centres.size());
    SweepSummaries groups;
    groups.resize(records.size(), records.size());
    SweepSummaries::Maker maker;
    CameraOdometers odometers;
    glm::dvec3 eye(0.0, 0.0, 0.0);
    double yaw = 0.0, pitch = 0.17;
    View view = viewAt(eye, yaw, pitch);
    int64_t tests = 0, steadyTests = 0;
    for (int32_t frame = 0; frame < frames; ++frame) {
        if (frame > 0) {
            const View next = viewAt(eye, yaw, pitch);
            odometers.move(view, next);
            view = next;
        }
        EXPECT_FALSE(odometers.beginUpdate());
        for (int32_t g = 0; g < groups.groups(); ++g) {
            const int32_t first = g * SweepSummaries::kGroup, end = std::min(int32_t(records.size()), first + SweepSummaries::kGroup);
            const bool skip = summaries && groups.canSkip(g, odometers);
            if (skip && skipped) ++*skipped;
            maker.start();
            std::vector<int32_t> due;
            for (int32_t i = first; i < end; ++i) {
                Record& r = records[size_t(i)];
                double s[4];
                slacks(view, centres[size_t(i)], radii[size_t(i)], s);
                if (skip || !odometers.usedUp(r.stamp, r.odometer, r.dist, r.rho)) {
                    const bool holds = r.plane >= 0 ? s[r.plane] < 0.0 : std::min({s[0], s[1], s[2], s[3]}) >= 0.0;
                    if (!holds) {
                        ADD_FAILURE() << (r.plane >= 0 ? "culled by a plane until its margin is used up" : "inside while its margin lasts")
                                      << (skip ? " (its group passed over)" : "") << ": sphere " << i << ", frame " << frame;
                        return -1;
                    }
                    // What judge() assumed of the up vector for the margin it gave (rho is at
                    // most that margin until a renewal, which only lowers what is left).
                    const double tilt = glm::length(upInView(view) - r.up);
                    if (r.rho >= 0.0f && tilt > CameraOdometers::tiltAllowed(r.rho0, r.testedDist, r.odometer)) {
                        ADD_FAILURE() << "the up vector tilted by " << tilt << " while a margin of " << r.rho0 << " at "
                                      << r.testedDist << " m lasts" << (skip ? " (its group passed over)" : "") << ": sphere " << i
                                      << ", frame " << frame;
                        return -1;
                    }
                    if (skip) continue;
                    maker.add(r.odometer, r.rho, r.dist, odometers.age(r.stamp), odometers.read(r.stamp, r.odometer, r.dist));
                    if (odometers.age(r.stamp) >= CameraOdometers::kHistory / 2) {
                        const CameraOdometers::Renewed renewed = odometers.renewed(r.stamp, r.odometer, r.dist, r.rho);
                        r.dist = renewed.dist, r.rho = renewed.rho, r.stamp = odometers.stamp();
                    }
                    continue;
                }
                due.push_back(i);
            }
            if (!skip) maker.finish(groups, g, odometers);
            for (int32_t i : due) {
                Record& r = records[size_t(i)];
                double s[4];
                slacks(view, centres[size_t(i)], radii[size_t(i)], s);
                ++tests; // as Refiner::judge: the plane the sphere lies furthest outside, or the slack inside
                double outside = 0.0, inside = 1e30;
                r.plane = -1;
                for (int32_t p = 0; p < 4; ++p) {
                    inside = std::min(inside, s[p]);
                    if (-s[p] > outside) outside = -s[p], r.plane = p;
                }
                r.odometer = r.plane >= 0 && planes ? Odometer(int32_t(Odometer::RightPlane) + r.plane) : odometers.moving();
                r.stamp = odometers.stamp();
                r.dist = float(glm::length(centres[size_t(i)] - view.eye) + 1.0); // rounded up, loosely
                r.rho = CameraOdometers::storedMargin(r.plane >= 0 ? outside : inside);
                r.testedDist = r.dist, r.rho0 = r.rho, r.up = upInView(view);
                if (r.odometer == Odometer::Steady) ++steadyTests;
                groups.set(i, r.odometer, r.dist, r.rho);
            }
        }
        if (frame >= flight.pauseFrom && frame < flight.pauseTo) continue;
        eye += glm::dvec3(std::sin(yaw), 0.0, -std::cos(yaw)) * (flight.forward * (1.0 + 0.5 * unit(rng))) +
               glm::dvec3(std::cos(yaw), 0.0, std::sin(yaw)) * (flight.sideways * unit(rng)) + glm::dvec3(0, flight.climb * unit(rng), 0);
        yaw += flight.turn * unit(rng);
        const bool nodding = flight.nodPeriod == 0 || 4 * (frame % flight.nodPeriod) >= 3 * flight.nodPeriod;
        pitch += 0.2 * flight.turn * unit(rng) + (nodding ? flight.nod * unit(rng) : 0.0);
    }
    if (steady) *steady += steadyTests;
    return tests;
}

// Flying straight and level, with bursts of nodding (the last quarter of every 40 frames).
Flight levelWithBursts() {
    Flight bursts{30.0, 10.0, 0.0, 0.0};
    bursts.nod = 0.01, bursts.nodPeriod = 40;
    return bursts;
}

} // namespace

TEST(CameraOdometers, AVerdictHoldsUntilItsOdometerUsesUpTheMarginAlsoAfterRenewals) {
    // Long enough that records are renewed (age kHistory / 2) and older stamps come round.
    const int32_t frames = int32_t(CameraOdometers::kHistory) * 2 + 40;
    fly({30.0, 10.0, 5.0, 0.0}, frames, 1);      // forward with sway and climb, no turn
    fly({30.0, 10.0, 5.0, 0.004}, frames, 2);    // and turning
    fly({0.0, 40.0, 20.0, 0.01}, frames, 3);     // sideways and turning
    fly({-30.0, 0.0, 0.0, 0.0}, frames, 4);      // backwards
    Flight nodding{0.0, 0.0, 0.0, 0.002};         // looking up and down from one place
    nodding.nod = 0.01;
    fly(nodding, frames, 9);
    // Flying straight and level, then nodding for a while: the verdicts made on the steady
    // odometer are charged for the tilt that follows.
    int64_t steady = 0;
    const int64_t tests = fly(levelWithBursts(), frames, 10, true, false, nullptr, &steady);
    std::printf("flying level with bursts of nodding: %lld tests, %lld of them on the steady odometer\n", (long long)tests,
                (long long)steady);
    EXPECT_GT(steady, tests / 10);
    EXPECT_LT(steady, tests);
}

TEST(CameraOdometers, FlyingForwardLeavesTheCellsBesideTheViewAlone) {
    // Straight ahead with a little sway: the cells outside a side plane move further out.
    const Flight forward{30.0, 3.0, 2.0, 0.0};
    const int64_t withPlanes = fly(forward, 200, 5), travelOnly = fly(forward, 200, 5, false);
    std::printf("tests over 200 frames of 3000 spheres flying forward: %lld with the planes' odometers, %lld on travel alone\n",
                (long long)withPlanes, (long long)travelOnly);
    ASSERT_GT(withPlanes, 0);
    EXPECT_LT(2 * withPlanes, travelOnly);
}

// The refiner's sweep passes over groups of records by their summaries: every verdict it
// passes over still holds, and it does pass over groups.
TEST(CameraOdometers, AGroupSummaryPassesOverNoRecordThatIsDue) {
    const int32_t frames = int32_t(CameraOdometers::kHistory) * 2 + 40;
    int64_t skipped = 0;
    fly({30.0, 10.0, 5.0, 0.0}, frames, 1, true, true, &skipped);
    fly({30.0, 10.0, 5.0, 0.004}, frames, 2, true, true, &skipped);
    fly({0.0, 40.0, 20.0, 0.01}, frames, 3, true, true, &skipped);
    fly({-30.0, 0.0, 0.0, 0.0}, frames, 4, true, true, &skipped);
    fly({3.0, 1.0, 0.5, 0.0005}, frames, 6, true, true, &skipped); // slowly: most groups passed over
    fly({40.0, 0.0, 0.0, 0.03}, frames, 7, true, true, &skipped);  // turning hard while flying on
    fly(levelWithBursts(), frames, 10, true, true, &skipped);
    // Still for longer than the odometers' history between two stretches of flight: what the
    // first stretch used up is not forgotten.
    Flight pause{60.0, 20.0, 10.0, 0.002};
    pause.pauseFrom = 30, pause.pauseTo = 30 + int32_t(CameraOdometers::kHistory) + 100;
    fly(pause, pause.pauseTo + 60, 8, true, true, &skipped);
    std::printf("groups passed over: %lld\n", (long long)skipped);
    EXPECT_GT(skipped, frames * 10);
}

TEST(CameraOdometers, AStillCameraUsesNoMargin) {
    CameraOdometers odometers;
    const View view = viewAt({0, 0, 0}, 0.3, 0.2);
    odometers.beginUpdate();
    const uint32_t stamp = odometers.stamp();
    for (int32_t frame = 0; frame < 10; ++frame) {
        odometers.move(view, view);
        odometers.beginUpdate();
        EXPECT_FALSE(odometers.usedUp(stamp, Odometer::Travel, 1000.0f, 0.0f)) << "a margin of 0 holds while nothing moves";
        EXPECT_TRUE(odometers.usedUp(stamp, Odometer::Travel, 1000.0f, -1.0f)) << "rho < 0: due";
    }
}
