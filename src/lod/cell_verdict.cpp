// The verdict of §5's criteria on one cell bound and its margin ("Hexagonal LOD for
// Interactive Terrain Rendering", Sußner, Dachsbacher, Greiner, VMV 2005); see cell_verdict.h.
#include "lod/cell_verdict.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lod/float_rounding.h"

namespace hexlod {

namespace {

// The largest margin in (0, cap] found to hold by bisection (the test is monotone: a
// verdict that holds within m holds within anything less), 0 when none, to an eighth of the
// cap. Four evaluations at most; three when the cap is known not to hold (tryCap false). A
// finer search costs more than the re-tests its longer margins save: on the Grand Canyon at
// 50 m a frame, 5 steps test 918 cells a frame, 3 steps 967, in 8 % less time; 2 steps 1,098.
template <typename Holds>
double largestMargin(double cap, Holds&& holds, bool tryCap = true) {
    if (!(cap > 0.0)) return 0.0;
    if (tryCap && cap < kForever && holds(cap)) return cap;
    double lo = 0.0, hi = std::min(cap, 1e12);
    for (int32_t k = 0; k < 3; ++k) {
        const double m = 0.5 * (lo + hi);
        if (holds(m)) lo = m;
        else hi = m;
    }
    return lo;
}

} // namespace

// The criteria of §5 for one bound (see view_criteria.h), and the margin of the verdict: how
// far the sphere's centre may move in view coordinates (the eye by as much in the world, the
// world's up vector in view coordinates by at most CameraOdometers::tiltAllowed(margin, dist)
// on the odometer the verdict is measured by) before the verdict can change.
//  - outside a side plane of the frustum: the distance beyond it (the planes are fixed in view
//    coordinates; near and far planes move with the camera, so they give no margin);
//  - back-facing: the smallest (v.n - r|n|)/|n| over the slope box's corners (v = centre - eye);
//  - projected error within tau: a margin m for which the bound over every sphere of radius
//    r + m around the centre, at depth >= z - r - m and with the up vector tilted by up to
//    CameraOdometers::tiltAllowed(m, dist, moving), stays within tau (projectedErrorPixels' corner
//    argument, plus the tilt's share);
//  - failing (asked for with failMargin, for merge tests): a margin that keeps the sphere
//    inside the side planes and the far plane, not back-facing, and a lower bound of the
//    projected error (at the centre's screen tangent, the nearest depth at most
//    max(z - r + m, mergeNearest): merge tests do not use the near plane) above tau, given
//    far >= kFarShrink farRef (or a far plane beyond the field: Refiner::setView).
// Without a margin known, 0: the cell is due at the next update.
CellVerdict judgeCell(const VerdictContext& context, const CellQuestion& cell, double& distOut) {
    const View& view = *context.view;
    const Footprint& f = cell.footprint;
    const CellError& e = cell.bound;
    const SlopeBox* slopes = cell.slopes;
    const bool failMargin = cell.failMargin;
    const Odometer moving = context.moving;
    CellVerdict v;
    v.odometer = moving;
    if (context.viewIndependent) {
        double error = e.error;
        if (!context.earth.flat()) {
            // The drawn surface also leaves the curved one by the chords' sag and drift (in drawn
            // metres: heights times the vertical scale; the error is in true metres).
            const CurvedCell curved = curvedCellOf(context.earth, f, e, context.verticalScale);
            error += (curved.sag + curved.drift) / context.verticalScale;
        }
        v.pass = !(error > context.maxError);
        v.pixels = error;
        v.margin = kForever;
        distOut = 0.0;
        return v;
    }
    glm::dvec3 center;
    double radius;
    // On the curved Earth: the sphere of the cell's image, its up vector and how far it turns,
    // and the sag of its straight triangles under the curved surface (earth_shape.h).
    const bool flat = context.earth.flat();
    CurvedCell curved;
    if (flat) {
        boundingSphere(f, e, context.verticalScale, center, radius);
    } else {
        curved = curvedCellOf(context.earth, f, e, context.verticalScale);
        center = curved.center, radius = curved.radius;
    }
    const glm::dvec3 d = center - view.eye;
    distOut = double(roundedUp(glm::length(d)));
    const double dist = distOut;
    const double x = glm::dot(d, view.right), y = glm::dot(d, view.up), z = glm::dot(d, view.forward);
    double inside = kForever; // smallest slack inside the side planes
    if (context.culling) {
        const double sx = context.planeNormX, sy = context.planeNormY;
        const double slack[4] = {(view.tanHalfX * z - x) / sx + radius, (view.tanHalfX * z + x) / sx + radius,
                                 (view.tanHalfY * z - y) / sy + radius, (view.tanHalfY * z + y) / sy + radius};
        double outside = 0.0;
        int32_t culledBy = 0;
        for (int32_t p = 0; p < 4; ++p) {
            inside = std::min(inside, slack[p]);
            if (-slack[p] > outside) outside = -slack[p], culledBy = p;
        }
        // Culled until the centre comes back across that plane: the plane's odometer.
        if (outside > 0.0) return {true, 0.0, outside, Odometer(int32_t(Odometer::RightPlane) + culledBy)};
        // In front of the near plane: an own test only (merge tests do not use the near plane).
        if ((!failMargin && z + radius < view.nearPlane) || z - radius > view.farPlane) return {true, 0.0, 0.0, moving};
    }
    double front = kForever; // how far the eye may move before a front-facing cell can turn its back
    if (context.backfaceCulling && slopes && slopes->known()) {
        // On the curved Earth the slopes' normals as drawn, allowed the surface's turn.
        const BackFaces faces = flat ? backFaces(view, center, radius, *slopes, context.verticalScale)
                                     : curvedBackFaces(view, context.earth, curved, *slopes, context.verticalScale);
        if (faces.backFacing) return {true, 0.0, faces.back, moving};
        front = std::min(kForever, faces.front);
    }
    const double error = double(e.error) * context.verticalScale;
    // A merge test bounds the error at the sphere's nearest depth however close to the eye, not
    // at the near plane: its verdict, and the margin of a failing one, then hold whatever near
    // plane later views have (the page's follows the height above the ground). It must be the
    // stricter test, so that a merge it allows is not split again by the own test: with a near
    // plane closer than context.mergeNearest (a walk a few centimetres above the ground), the near
    // plane. (Otherwise a teleport to such a walk split and merged 1984 cells every update.) A
    // passing merge's margin holds for any near plane (upper() ignores it), and a failing one's
    // lower bound, taken at context.mergeNearest, holds for every nearer depth.
    const double nearest = failMargin ? std::min(context.mergeNearest, view.nearPlane) : view.nearPlane;
    v.pixels = flat ? projectedErrorPixels(view, center, radius, error, nearest) : projectedErrorPixels(view, curved, error, nearest);
    const double t = context.tau;
    v.pass = !(v.pixels > t);
    if (error <= 0.0 && curved.sag <= 0.0 && curved.drift <= 0.0) {
        v.margin = kForever;
        return v;
    }
    // The up vector the error stands along, in view coordinates: the world's, or the cell's.
    const double ux = flat ? view.right.y : glm::dot(view.right, curved.up), uy = flat ? view.up.y : glm::dot(view.up, curved.up),
                 uz = flat ? view.forward.y : glm::dot(view.forward, curved.up);
    // On the curved Earth the cell's normals turn by up to curved.tilt besides the camera's
    // tilt, the sag adds to the error along them, and the drift is a displacement in any
    // direction: the turn and the drift times the largest projected length of a unit vector
    // (anyDirectionGain). On the plane the arithmetic is the flat bound's, unchanged.
    if (v.pass) {
        // Upper bound of the projected error over every view within margin m (the sum of the
        // two squares is largest where each is: the corner maximum of projectedErrorPixels).
        auto upper = [&](double m) {
            const double zLow = z - radius - m;
            if (!(zLow > 0.0)) return kForever;
            const double r = radius + m, toLow = 1.0 / zLow, toHigh = 1.0 / (z + r);
            auto range = [&](double c, double& lo, double& hi) {
                const double a = c - r, b = c + r;
                lo = a * (a < 0.0 ? toLow : toHigh);
                hi = b * (b > 0.0 ? toLow : toHigh);
            };
            double xLo, xHi, yLo, yHi;
            range(x, xLo, xHi);
            range(y, yLo, yHi);
            const double gx = std::max((ux - xLo * uz) * (ux - xLo * uz), (ux - xHi * uz) * (ux - xHi * uz));
            const double gy = std::max((uy - yLo * uz) * (uy - yLo * uz), (uy - yHi * uz) * (uy - yHi * uz));
            const double tMax2 = std::max(xLo * xLo, xHi * xHi) + std::max(yLo * yLo, yHi * yHi);
            const double tilt = dist > 0.0 ? CameraOdometers::tiltAllowed(m, dist, moving) : kForever;
            if (flat) return view.pixelsPerTangent * error * (std::sqrt(gx + gy) + tilt * std::sqrt(1.0 + tMax2)) * toLow;
            const double any = anyDirectionGain(tMax2);
            return view.pixelsPerTangent *
                   ((error + curved.sag) * (std::sqrt(gx + gy) + tilt * std::sqrt(1.0 + tMax2) + curved.tilt * any) + curved.drift * any) * toLow;
        };
        // At that cap the depth alone has used up the room the error had below tau, so the bound
        // there (its other terms only grow with m) is above tau: no need to try it.
        v.margin = largestMargin((z - radius) * (1.0 - v.pixels / t), [&](double m) { return upper(m) <= t; }, false);
        return v;
    }
    if (!failMargin) return v;
    // Lower bound of the projected error over every view within margin m.
    if (!(z > 0.0)) return v;
    const double tcx = x / z, tcy = y / z;
    const double pcx = ux - tcx * uz, pcy = uy - tcy * uz;
    const double pc = std::sqrt(pcx * pcx + pcy * pcy);
    const double tangentSpeed = std::sqrt((1.0 + std::abs(tcx)) * (1.0 + std::abs(tcx)) + (1.0 + std::abs(tcy)) * (1.0 + std::abs(tcy)));
    const double tangent = std::sqrt(tcx * tcx + tcy * tcy);
    auto lower = [&](double m) {
        // The centre stays in front of the eye (its screen tangent is then in the box the bound
        // maximises over), and the sphere short of the far plane when culling.
        if (z - m < context.mergeNearest || (context.culling && !context.farCoversData && z - radius + m > kFarShrink * context.farRef)) return 0.0;
        const double dt = m * tangentSpeed / (z - m);
        const double tc = tangent + dt;
        const double tilt = dist > 0.0 ? CameraOdometers::tiltAllowed(m, dist, moving) : kForever;
        const double any = anyDirectionGain(tc * tc);
        const double g = pc - std::abs(uz) * dt - tilt * std::sqrt(1.0 + tc * tc) - (flat ? 0.0 : curved.tilt * any);
        const double shown = flat ? error * g : (error - curved.sag) * g - curved.drift * any;
        if (!(g > 0.0 && shown > 0.0)) return 0.0;
        return (flat ? view.pixelsPerTangent * error * g : view.pixelsPerTangent * shown) / std::max(z - radius + m, context.mergeNearest);
    };
    const double atCenter = view.pixelsPerTangent * error * pc / std::max(z - radius, context.mergeNearest);
    // Strictly inside the side planes and in front: a margin just below those slacks.
    // As in the passing case, the bound at the first of these caps is not above tau: only a
    // cap set by a side plane or the back faces is worth trying.
    const double depthCap = (z - radius) * (atCenter / t - 1.0);
    const double cap = std::min({depthCap, 0.999 * inside, 0.999 * front});
    v.margin = largestMargin(cap, [&](double m) { return lower(m) > t; }, cap < depthCap);
    return v;
}


void tighten(CellVerdict& into, const CellVerdict& other) {
    if (other.margin >= kForever) return;
    if (into.margin >= kForever) {
        into.margin = other.margin, into.odometer = other.odometer;
        return;
    }
    // Steady charges at least what any other odometer does, travel at least what a plane's does.
    if (into.odometer != other.odometer)
        into.odometer = into.odometer == Odometer::Steady || other.odometer == Odometer::Steady ? Odometer::Steady : Odometer::Travel;
    into.margin = std::min(into.margin, other.margin);
}

} // namespace hexlod
