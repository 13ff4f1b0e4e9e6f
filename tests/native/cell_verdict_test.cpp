// The verdict and its margin (lod/cell_verdict.h) by invariant, on random cells and cameras:
// a verdict holds for every camera within its margin, passes more as tau grows, never has a
// negative margin, and never passes a visible cell whose §5 bound exceeds tau.
#include "lod/cell_verdict.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>

#include "views.h"

namespace hexlod {
namespace {

// A cell in a 20 km square, up to 2 km across, with heights and an error bound of metres.
struct RandomCell {
    Footprint footprint;
    CellError bound;
    SlopeBox slopes;
};

class Cases {
public:
    explicit Cases(uint32_t seed) : rng_(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

    RandomCell cell() {
        RandomCell c;
        const double x = uniform(0.0, 20000.0), z = uniform(0.0, 20000.0), size = std::exp(uniform(std::log(20.0), std::log(2000.0)));
        c.footprint = {float(x), float(x + size), float(z), float(z + size * uniform(0.5, 1.0))};
        const double low = uniform(0.0, 2000.0);
        c.bound.low = float(low);
        c.bound.high = float(low + uniform(0.0, 800.0));
        c.bound.error = float(uniform(0.0, 1.0) < 0.05 ? 0.0 : std::exp(uniform(std::log(0.01), std::log(100.0))));
        const double dx = uniform(-1.5, 1.5), dz = uniform(-1.5, 1.5);
        c.slopes = {float(dx), float(dx + uniform(0.0, 0.5)), float(dz), float(dz + uniform(0.0, 0.5))};
        return c;
    }
    // A camera over the square, looking somewhere along it, mostly down.
    View view() {
        View v = test::viewAt({uniform(-2000.0, 22000.0), uniform(100.0, 6000.0), uniform(-2000.0, 22000.0)}, uniform(-3.14, 3.14),
                              uniform(-0.2, 1.2));
        v.pixelsPerTangent = 1080.0 / (2.0 * v.tanHalfY);
        v.nearPlane = 1.0;
        v.farPlane = 1e12;
        return v;
    }
    // A unit vector in a random direction.
    glm::dvec3 direction() {
        glm::dvec3 d;
        do d = {uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)};
        while (glm::length(d) < 0.1 || glm::length(d) > 1.0);
        return glm::normalize(d);
    }

private:
    std::mt19937 rng_;
};

VerdictContext contextFor(const View& view, double tau) {
    VerdictContext context;
    context.view = &view;
    context.planeNormX = std::sqrt(1.0 + view.tanHalfX * view.tanHalfX);
    context.planeNormY = std::sqrt(1.0 + view.tanHalfY * view.tanHalfY);
    context.tau = tau;
    context.mergeNearest = 1e-3;
    context.farCoversData = true; // the far plane (1e12 m) culls nothing
    context.farRef = view.farPlane;
    return context;
}

glm::dvec3 centreOf(const RandomCell& cell) {
    glm::dvec3 centre;
    double radius;
    boundingSphere(cell.footprint, cell.bound, 1.0, centre, radius);
    return centre;
}

// v rotated by `angle` radians about the unit `axis` (Rodrigues).
glm::dvec3 rotated(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
    return v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) + axis * glm::dot(axis, v) * (1.0 - std::cos(angle));
}

// The view moved by `travel` and turned by `angle` about `axis`; `turn` gets the Frobenius norm
// of the change of its basis (camera_odometers.h), which is that of the rotation minus identity.
View moved(const View& from, const glm::dvec3& travel, const glm::dvec3& axis, double angle, double& turn) {
    View to = from;
    to.eye += travel;
    to.right = rotated(from.right, axis, angle);
    to.up = rotated(from.up, axis, angle);
    to.forward = rotated(from.forward, axis, angle);
    turn = std::sqrt(glm::dot(to.right - from.right, to.right - from.right) + glm::dot(to.up - from.up, to.up - from.up) +
                     glm::dot(to.forward - from.forward, to.forward - from.forward));
    return to;
}

// Moves the camera within the verdict's margin in random ways (a share of it travelled, the
// rest turned: a centre at distance D moves by travel + turn * (D + travel), the charge of the
// travel odometer) and judges again: the verdict must be the same.
// The first moves go all the way in the worst directions for a passing error: straight
// towards the centre, and towards it while turning to look along the bound's vertical.
template <typename Check>
void moveWithinMargin(Cases& cases, const View& view, const CellVerdict& verdict, double dist, const glm::dvec3& centre, Check&& check) {
    if (!(verdict.margin > 0.0)) return;
    const double reach = std::min(verdict.margin, 1e6) * 0.999;
    const glm::dvec3 towards = glm::normalize(centre - view.eye);
    double turn;
    check(moved(view, std::min(reach, 0.999 * dist) * towards, {1, 0, 0}, 0.0, turn));
    check(moved(view, 0.5 * std::min(reach, 0.999 * dist) * towards, view.right, 0.5 * reach / (dist + reach) / std::sqrt(2.0), turn));
    check(moved(view, 0.5 * std::min(reach, 0.999 * dist) * towards, view.right, -0.5 * reach / (dist + reach) / std::sqrt(2.0), turn));
    for (int32_t k = 0; k < 8; ++k) {
        const double budget = std::min(verdict.margin, 1e6) * cases.uniform(0.0, 0.999);
        const double travel = budget * cases.uniform(0.0, 1.0);
        const double angleBudget = (budget - travel) / (dist + travel); // turn allowed
        // |R - I|_F = 2 sqrt(2) sin(angle / 2) <= sqrt(2) angle
        const double angle = std::min(angleBudget / std::sqrt(2.0), 0.5) * cases.uniform(0.0, 1.0);
        double turn;
        const View to = moved(view, travel * cases.direction(), cases.direction(), angle, turn);
        ASSERT_LE(travel + turn * (dist + travel), verdict.margin);
        check(to);
    }
}

TEST(CellVerdict, APassingVerdictHoldsForEveryCameraWithinItsMargin) {
    Cases cases(1);
    int32_t passes = 0, withMargin = 0;
    for (int32_t i = 0; i < 4000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        const double tau = std::exp(cases.uniform(std::log(0.3), std::log(8.0)));
        VerdictContext context = contextFor(view, tau);
        context.backfaceCulling = i % 2 == 0;
        const CellQuestion question{cell.footprint, cell.bound, &cell.slopes, i % 3 == 0};
        double dist;
        const CellVerdict verdict = judgeCell(context, question, dist);
        if (!verdict.pass) continue;
        ++passes;
        withMargin += verdict.margin > 0.0 ? 1 : 0;
        moveWithinMargin(cases, view, verdict, dist, centreOf(cell), [&](const View& to) {
            VerdictContext there = contextFor(to, tau);
            there.backfaceCulling = context.backfaceCulling;
            double d;
            const CellVerdict again = judgeCell(there, question, d);
            ASSERT_TRUE(again.pass) << "cell " << i << ": passed with margin " << verdict.margin << " m, fails "
                                    << glm::length(to.eye - view.eye) << " m away at " << again.pixels << " px (tau " << tau << ")";
        });
        if (HasFatalFailure()) return;
    }
    EXPECT_GT(passes, 1000);
    EXPECT_GT(withMargin, 500) << "margins worth testing";
}

TEST(CellVerdict, AFailingMergeVerdictHoldsForEveryCameraWithinItsMargin) {
    Cases cases(2);
    int32_t fails = 0, withMargin = 0;
    for (int32_t i = 0; i < 20000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        const double tau = std::exp(cases.uniform(std::log(0.3), std::log(8.0)));
        const VerdictContext context = contextFor(view, tau);
        const CellQuestion question{cell.footprint, cell.bound, nullptr, true}; // a merge test, as the refiner asks it
        double dist;
        const CellVerdict verdict = judgeCell(context, question, dist);
        if (verdict.pass) continue;
        ++fails;
        withMargin += verdict.margin > 0.0 ? 1 : 0;
        moveWithinMargin(cases, view, verdict, dist, centreOf(cell), [&](const View& to) {
            double d;
            const CellVerdict again = judgeCell(contextFor(to, tau), question, d);
            ASSERT_FALSE(again.pass) << "cell " << i << ": failed with margin " << verdict.margin << " m, passes "
                                     << glm::length(to.eye - view.eye) << " m away";
        });
        if (HasFatalFailure()) return;
    }
    EXPECT_GT(fails, 500);
    EXPECT_GT(withMargin, 200) << "margins worth testing";
}

TEST(CellVerdict, AVerdictIsMonotoneInTau) {
    Cases cases(3);
    for (int32_t i = 0; i < 4000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        const double tau = std::exp(cases.uniform(std::log(0.1), std::log(10.0)));
        const double larger = tau * cases.uniform(1.0, 4.0);
        const CellQuestion question{cell.footprint, cell.bound, &cell.slopes, i % 2 == 0};
        double dist;
        const CellVerdict strict = judgeCell(contextFor(view, tau), question, dist);
        const CellVerdict loose = judgeCell(contextFor(view, larger), question, dist);
        ASSERT_EQ(strict.pixels, loose.pixels) << "cell " << i << ": the projected error does not depend on tau";
        if (strict.pass) {
            ASSERT_TRUE(loose.pass) << "cell " << i << ": passes at tau " << tau << ", fails at " << larger;
        }
    }
}

TEST(CellVerdict, MarginsAreNeverNegative) {
    Cases cases(4);
    for (int32_t i = 0; i < 4000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        VerdictContext context = contextFor(view, std::exp(cases.uniform(std::log(0.1), std::log(10.0))));
        context.viewIndependent = i % 7 == 0;
        context.maxError = cases.uniform(0.01, 50.0);
        context.culling = i % 5 != 0;
        context.farCoversData = i % 3 != 0; // else the far plane bounds the margins of failing merge tests
        const CellQuestion question{cell.footprint, cell.bound, i % 2 == 0 ? &cell.slopes : nullptr, i % 4 < 2};
        double dist;
        const CellVerdict verdict = judgeCell(context, question, dist);
        ASSERT_GE(verdict.margin, 0.0) << "cell " << i;
        ASSERT_GE(dist, 0.0) << "cell " << i;
        ASSERT_GE(verdict.pixels, 0.0) << "cell " << i;
    }
}

// Without culling, the verdict is the §5 bound against tau, exactly; with culling, a cell in
// front of the near plane, inside every side plane and facing the camera is still judged by it.
TEST(CellVerdict, ACellWhoseBoundExceedsTauIsNeverJudgedFine) {
    Cases cases(5);
    int32_t exceeding = 0;
    for (int32_t i = 0; i < 4000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        const double tau = std::exp(cases.uniform(std::log(0.1), std::log(10.0)));
        VerdictContext context = contextFor(view, tau);
        context.culling = i % 2 == 0;
        context.backfaceCulling = context.culling;
        glm::dvec3 center;
        double radius;
        boundingSphere(cell.footprint, cell.bound, context.verticalScale, center, radius);
        const bool hidden = context.culling && (outsideFrustum(view, center, radius) ||
                                                backFaces(view, center, radius, cell.slopes, context.verticalScale).backFacing);
        const double bound = projectedErrorPixels(view, center, radius, double(cell.bound.error) * context.verticalScale);
        double dist;
        const CellVerdict verdict = judgeCell(context, {cell.footprint, cell.bound, &cell.slopes, false}, dist);
        if (bound > tau && !hidden) {
            ++exceeding;
            ASSERT_FALSE(verdict.pass) << "cell " << i << ": " << bound << " px on screen, tau " << tau;
        }
        if (!context.culling) {
            ASSERT_EQ(verdict.pass, !(bound > tau)) << "cell " << i;
        }
    }
    EXPECT_GT(exceeding, 500);
}

TEST(CellVerdict, TheViewIndependentVerdictIsTheErrorAgainstMaxErrorForever) {
    Cases cases(6);
    for (int32_t i = 0; i < 1000; ++i) {
        const RandomCell cell = cases.cell();
        const View view = cases.view();
        VerdictContext context = contextFor(view, 1.0);
        context.viewIndependent = true;
        context.maxError = cases.uniform(0.01, 50.0);
        double dist = -1.0;
        const CellVerdict verdict = judgeCell(context, {cell.footprint, cell.bound, &cell.slopes, i % 2 == 0}, dist);
        ASSERT_EQ(verdict.pass, !(cell.bound.error > context.maxError));
        ASSERT_GE(verdict.margin, kForever);
        ASSERT_EQ(dist, 0.0);
    }
}

TEST(CellVerdict, TightenKeepsTheSmallerMarginOnAnOdometerThatChargesBoth) {
    CellVerdict a{true, 0.5, 10.0, Odometer::RightPlane}, b{true, 0.2, 4.0, Odometer::LeftPlane};
    tighten(a, b);
    EXPECT_EQ(a.margin, 4.0);
    EXPECT_EQ(a.odometer, Odometer::Travel) << "two planes: the travel bounds both";
    CellVerdict steady{true, 0.0, 7.0, Odometer::Steady};
    tighten(steady, CellVerdict{true, 0.0, 9.0, Odometer::Travel});
    EXPECT_EQ(steady.margin, 7.0);
    EXPECT_EQ(steady.odometer, Odometer::Steady);
    CellVerdict forever{true, 0.0, kForever, Odometer::Travel};
    tighten(forever, CellVerdict{true, 0.0, 3.0, Odometer::TopPlane});
    EXPECT_EQ(forever.margin, 3.0);
    EXPECT_EQ(forever.odometer, Odometer::TopPlane);
}

} // namespace
} // namespace hexlod
