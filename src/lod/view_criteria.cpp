// Refinement criteria of paper §5, made a bound; see view_criteria.h.
#include "lod/view_criteria.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace hexlod {

bool makeView(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double tanHalfFovY,
              double aspect, double viewportHeightPx, double nearPlane, double farPlane, View& view) {
    const glm::dvec3 toward = target - eye;
    const double distance = glm::length(toward);
    if (!(distance > 0.0) || !(tanHalfFovY > 0.0) || !(aspect > 0.0) || !(viewportHeightPx > 0.0) ||
        !(nearPlane > 0.0) || !(farPlane > nearPlane))
        return false;
    const glm::dvec3 forward = toward / distance;
    glm::dvec3 right = glm::cross(forward, up);
    const double rightLength = glm::length(right);
    if (!(rightLength > 1e-9)) return false;
    right /= rightLength;
    view.eye = eye;
    view.forward = forward;
    view.right = right;
    view.up = glm::cross(right, forward);
    view.tanHalfY = tanHalfFovY;
    view.tanHalfX = tanHalfFovY * aspect;
    view.pixelsPerTangent = viewportHeightPx / (2.0 * tanHalfFovY);
    view.nearPlane = nearPlane;
    view.farPlane = farPlane;
    return true;
}

void boundingSphere(const Footprint& f, const CellError& e, double verticalScale, glm::dvec3& center, double& radius) {
    const glm::dvec3 low(f.x0, double(e.low) * verticalScale, f.z0), high(f.x1, double(e.high) * verticalScale, f.z1);
    center = 0.5 * (low + high);
    radius = 0.5 * glm::length(high - low);
}

CurvedCell curvedCellOf(const EarthShape& earth, const Footprint& f, const CellError& e, double verticalScale) {
    glm::dvec3 center;
    double radius;
    boundingSphere(f, e, verticalScale, center, radius);
    const double halfDiagonal = 0.5 * std::hypot(double(f.x1) - double(f.x0), double(f.z1) - double(f.z0));
    return curvedCell(earth, center, radius, halfDiagonal, double(e.low) * verticalScale, double(e.high) * verticalScale);
}

bool outsideFrustum(const View& view, const glm::dvec3& center, double radius) {
    const glm::dvec3 d = center - view.eye;
    const double x = glm::dot(d, view.right), y = glm::dot(d, view.up), z = glm::dot(d, view.forward);
    if (z + radius < view.nearPlane || z - radius > view.farPlane) return true;
    // Side planes through the eye: inside is |x| <= tanHalfX * z (and likewise y).
    const double sx = std::sqrt(1.0 + view.tanHalfX * view.tanHalfX), sy = std::sqrt(1.0 + view.tanHalfY * view.tanHalfY);
    if ((view.tanHalfX * z - x) / sx < -radius || (view.tanHalfX * z + x) / sx < -radius) return true;
    if ((view.tanHalfY * z - y) / sy < -radius || (view.tanHalfY * z + y) / sy < -radius) return true;
    return false;
}

namespace {

// The back-face test in a frame whose east, up and south (drawn metres per flat metre) are
// given, each slope's normal allowed to turn by `turn` radians. On the plane (the identity
// frame, no turn) the arithmetic is exactly (v . n - radius |n|) / |n|.
BackFaces facesAway(const View& view, const glm::dvec3& center, double radius, const glm::dvec3& east, const glm::dvec3& up,
                    const glm::dvec3& south, double turn, const SlopeBox& slopes, double s) {
    BackFaces faces;
    faces.front = std::numeric_limits<double>::infinity(); // without a test, never back-facing
    if (!slopes.known() || !(turn < 1.5)) return faces;    // nothing can be said: no margin either
    const double cosTurn = std::cos(turn), sinTurn = std::sin(turn);
    const glm::dvec3 v = center - view.eye;
    const double distance = turn > 0.0 ? glm::length(v) : 0.0;
    // Moving the eye by m moves v . n / |n| and |v| by at most m each.
    const double rate = cosTurn + sinTurn;
    double back = std::numeric_limits<double>::infinity(), frontFacing = -std::numeric_limits<double>::infinity();
    bool backFacing = true;
    // v . n - radius * |n| is concave in the slope (n is linear in it), so its smallest value
    // over the box is at one of the four corners.
    for (double dx : {double(slopes.dxLow), double(slopes.dxHigh)})
        for (double dz : {double(slopes.dzLow), double(slopes.dzHigh)}) {
            const glm::dvec3 n = glm::cross(south + s * dz * up, east + s * dx * up);
            const double length = glm::length(n);
            const double slack = (cosTurn * glm::dot(v, n) - (sinTurn * distance + radius) * length) / length / rate;
            if (slack <= 0.0) backFacing = false;
            back = std::min(back, slack);
            frontFacing = std::max(frontFacing, -slack);
        }
    faces.backFacing = backFacing;
    faces.back = back;
    faces.front = frontFacing;
    return faces;
}

} // namespace

BackFaces backFaces(const View& view, const glm::dvec3& center, double radius, const SlopeBox& slopes, double verticalScale) {
    return facesAway(view, center, radius, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 0.0, slopes, verticalScale);
}

BackFaces curvedBackFaces(const View& view, const EarthShape& earth, const CurvedCell& curved, const SlopeBox& slopes, double verticalScale) {
    if (!slopes.known()) return facesAway(view, curved.center, curved.radius, {}, {}, {}, 0.0, slopes, verticalScale);
    const double steepest = verticalScale * (std::max(std::abs(double(slopes.dxLow)), std::abs(double(slopes.dxHigh))) +
                                             std::max(std::abs(double(slopes.dzLow)), std::abs(double(slopes.dzHigh))));
    const CurvedJacobian jacobian = curvedJacobian(earth, curved);
    return facesAway(view, curved.center, curved.radius, jacobian.east, curved.up, jacobian.south,
                     curved.tilt + jacobian.stretchChange * steepest, slopes, verticalScale);
}

double projectedErrorPixels(const View& view, const glm::dvec3& center, double radius, double verticalError) {
    return projectedErrorPixels(view, center, radius, verticalError, view.nearPlane);
}

namespace {

// The screen tangents X/Z and Y/Z over a sphere at view coordinates (x, y, z), with depths in
// [zMin, zMax].
struct TangentBox {
    double xLo, xHi, yLo, yHi;
    TangentBox(double x, double y, double radius, double zMin, double zMax) {
        auto range = [&](double c, double& lo, double& hi) {
            const double a = c - radius, b = c + radius;
            lo = a < 0.0 ? a / zMin : a / zMax;
            hi = b > 0.0 ? b / zMin : b / zMax;
        };
        range(x, xLo, xHi);
        range(y, yLo, yHi);
    }
    // The largest length of the projected vector (ux, uy, uz) (view coordinates) over the box:
    // (ux - tx uz, uy - ty uz) has a length convex in (tx, ty), largest at a corner, the one
    // where each of its two squares is largest.
    double gain(double ux, double uy, double uz) const {
        const double gx = std::max((ux - xLo * uz) * (ux - xLo * uz), (ux - xHi * uz) * (ux - xHi * uz));
        const double gy = std::max((uy - yLo * uz) * (uy - yLo * uz), (uy - yHi * uz) * (uy - yHi * uz));
        return std::sqrt(gx + gy);
    }
    double tMax2() const { return std::max(xLo * xLo, xHi * xHi) + std::max(yLo * yLo, yHi * yHi); }
};

} // namespace

double projectedErrorPixels(const View& view, const glm::dvec3& center, double radius, double verticalError, double nearest) {
    if (verticalError <= 0.0) return 0.0;
    const glm::dvec3 d = center - view.eye;
    const double x = glm::dot(d, view.right), y = glm::dot(d, view.up), z = glm::dot(d, view.forward);
    const double zMin = std::max(z - radius, nearest), zMax = std::max(z + radius, zMin);
    // World up in view coordinates; the Jacobian of (X/Z, Y/Z) times it is
    // (ux - tx * uz, uy - ty * uz) / Z.
    const TangentBox box(x, y, radius, zMin, zMax);
    return view.pixelsPerTangent * verticalError * box.gain(view.right.y, view.up.y, view.forward.y) / zMin;
}

double projectedErrorPixels(const View& view, const CurvedCell& curved, double verticalError, double nearest) {
    if (verticalError <= 0.0 && curved.sag <= 0.0 && curved.drift <= 0.0) return 0.0;
    const glm::dvec3 d = curved.center - view.eye;
    const double x = glm::dot(d, view.right), y = glm::dot(d, view.up), z = glm::dot(d, view.forward);
    const double zMin = std::max(z - curved.radius, nearest), zMax = std::max(z + curved.radius, zMin);
    const TangentBox box(x, y, curved.radius, zMin, zMax);
    const double g = box.gain(glm::dot(view.right, curved.up), glm::dot(view.up, curved.up), glm::dot(view.forward, curved.up));
    const double any = anyDirectionGain(box.tMax2());
    // The error and the sag stand along normals within the tilt of up; the drift in any direction.
    return view.pixelsPerTangent * ((std::max(0.0, verticalError) + curved.sag) * (g + curved.tilt * any) + curved.drift * any) / zMin;
}

} // namespace hexlod
