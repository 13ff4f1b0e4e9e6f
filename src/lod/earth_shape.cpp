// The curved Earth's positions and cell bounds; see earth_shape.h.
#include "lod/earth_shape.h"

#include <algorithm>
#include <cmath>

namespace hexlod {

namespace {

constexpr double kHalfPi = 1.5707963267948966;

// The sphere wrap: the flat offset (dx, dz) from the origin becomes the point at that distance
// along the great circle in that direction. sinc = R sin(d / R) / d.
double wrapFactor(double d, double radius) { return d > 1e-9 * radius ? radius * std::sin(d / radius) / d : 1.0; }

// Geographic: the flat point's latitude and longitude offset from the origin, radians.
void geographicAngles(const EarthShape& e, double x, double z, double& phi, double& dLambda) {
    phi = e.latitude0 - (z - e.originZ) / e.metresPerRadianZ;
    dLambda = (x - e.originX) / e.metresPerRadianX;
}

} // namespace

glm::dvec3 curvedPosition(const EarthShape& e, double x, double h, double z) {
    if (e.kind == EarthKind::Sphere) {
        const double dx = x - e.originX, dz = z - e.originZ, d = std::hypot(dx, dz), R = e.radius;
        const double along = (R + h) * wrapFactor(d, R) / R; // (R + h) sin(d / R) / d
        return {along * dx, (R + h) * std::cos(d / R) - R, along * dz};
    }
    if (e.kind == EarthKind::Geographic) {
        double phi, dLambda;
        geographicAngles(e, x, z, phi, dLambda);
        const double s = std::sin(phi), c = std::cos(phi), s0 = std::sin(e.latitude0), c0 = std::cos(e.latitude0);
        const double n = kWgs84A / std::sqrt(1.0 - kWgs84E2 * s * s), n0 = kWgs84A / std::sqrt(1.0 - kWgs84E2 * s0 * s0);
        // Earth-centred, with the origin's meridian as longitude 0, minus the origin.
        const double X = (n + h) * c * std::cos(dLambda) - n0 * c0, Y = (n + h) * c * std::sin(dLambda);
        const double Z = (n * (1.0 - kWgs84E2) + h) * s - n0 * (1.0 - kWgs84E2) * s0;
        const double north = -s0 * X + c0 * Z, up = c0 * X + s0 * Z;
        return {Y, up, -north};
    }
    return {x, h, z};
}

glm::dvec3 curvedUp(const EarthShape& e, double x, double z) {
    if (e.kind == EarthKind::Sphere) {
        const double dx = x - e.originX, dz = z - e.originZ, d = std::hypot(dx, dz), R = e.radius;
        const double along = wrapFactor(d, R) / R; // sin(d / R) / d
        return {along * dx, std::cos(d / R), along * dz};
    }
    if (e.kind == EarthKind::Geographic) {
        double phi, dLambda;
        geographicAngles(e, x, z, phi, dLambda);
        const double s = std::sin(phi), c = std::cos(phi), s0 = std::sin(e.latitude0), c0 = std::cos(e.latitude0);
        const double X = c * std::cos(dLambda), Y = c * std::sin(dLambda);
        return {Y, c0 * X + s0 * s, -(-s0 * X + c0 * s)};
    }
    return {0.0, 1.0, 0.0};
}

// The bound rests on three properties of the map from flat (x, h, z) to the drawn frame, each
// over the flat sphere (tests/native/earth_shape_test.cpp checks them by brute force):
// - its Jacobian's columns are orthogonal (east, up, north), of lengths stretchX, 1 and
//   stretchZ, so points within r of the centre are drawn within max(1, stretches) r of its image;
// - it is linear in h along the unit normal, so a vertical error e is drawn as e along the normal;
// - its second derivative: in a horizontal direction at most normalXX along the normal and
//   tangentXX across it; between a horizontal direction and h (the normal turning) at most
//   tangentXH, across it. Linear interpolation over a triangle with vertices v_i and
//   barycentric weights l_i misses a function by 1/2 sum l_i H[v_i - p, v_i - p]; with the
//   vertices in the footprint (within halfDiagonal of its centre horizontally, and within half
//   the height range of the middle height) that is at most 1/2 normalXX halfDiagonal^2 along the
//   normal (the sag) and 1/2 (tangentXX halfDiagonal^2 + tangentXH halfDiagonal (high - low))
//   across it (the drift).
CurvedCell curvedCell(const EarthShape& e, const glm::dvec3& c, double r, double halfDiagonal, double low, double high) {
    CurvedCell cell;
    cell.center = curvedPosition(e, c.x, c.y, c.z);
    cell.up = curvedUp(e, c.x, c.z);
    const double hMax = std::max(0.0, c.y + r);
    double stretch = 1.0, normalXX = 0.0, tangentXX = 0.0, tangentXH = 0.0;
    if (e.kind == EarthKind::Sphere) {
        const double R = e.radius;
        const double farthest = std::hypot(c.x - e.originX, c.z - e.originZ) + r;
        stretch = (R + hMax) / R;
        cell.tilt = r / R; // the wrap shortens no radial distance and lengthens no other
        // A great circle's curvature; off the great circles through the origin, lines bend in
        // the surface by up to about (distance / R) / R.
        normalXX = (R + hMax) / (R * R);
        tangentXX = normalXX * 2.0 * farthest / R;
        tangentXH = 1.0 / R;
    } else if (e.kind == EarthKind::Geographic) {
        const double kx = e.metresPerRadianX, kz = e.metresPerRadianZ;
        const double north = std::min(kHalfPi, e.latitude0 - (c.z - r - e.originZ) / kz);
        const double south = std::max(-kHalfPi, e.latitude0 - (c.z + r - e.originZ) / kz);
        const double cosMax = south <= 0.0 && north >= 0.0 ? 1.0 : std::max(std::cos(south), std::cos(north));
        const double sinMax = std::min(1.0, std::max(std::abs(std::sin(south)), std::abs(std::sin(north))));
        const double w2 = 1.0 - kWgs84E2 * sinMax * sinMax;
        const double nMax = kWgs84A / std::sqrt(w2), mMax = kWgs84A * (1.0 - kWgs84E2) / (w2 * std::sqrt(w2));
        const double stretchX = (nMax + hMax) * cosMax / kx, stretchZ = (mMax + hMax) / kz;
        stretch = std::max({1.0, stretchX, stretchZ});
        cell.tilt = r / kz + r * cosMax / kx; // the normal turns a radian per radian of latitude, cos(latitude) per radian of longitude
        // Second derivatives per flat metre. A parallel (radius rho = (N + h) cos(phi)) curves
        // by rho / kx^2 towards the axis: cos(phi) of that along the normal, sin(phi) across
        // it. A meridian curves by (M + h) / kz^2 along the normal and |dM/dphi| / kz^2 across
        // it. Across both, |d rho / dphi| / (kx kz) along the parallel. On WGS 84
        // |dM/dphi| < 0.011 a and |dN/dphi| < 0.004 a.
        const double rho = (nMax + hMax) * cosMax;
        normalXX = std::max(rho * cosMax / (kx * kx), (mMax + hMax) / (kz * kz));
        tangentXX = rho * sinMax / (kx * kx) + 0.02 * kWgs84A / (kz * kz) + ((nMax + hMax) * sinMax + 0.01 * kWgs84A) / (kx * kz);
        tangentXH = cosMax / kx + 1.0 / kz;
    } else {
        cell.center = c;
        cell.radius = r;
        return cell;
    }
    cell.flatCenter = c, cell.flatRadius = r, cell.heightSpan = std::max(0.0, high - low);
    cell.radius = stretch * r;
    cell.sag = 0.5 * normalXX * halfDiagonal * halfDiagonal;
    cell.drift = 0.5 * (tangentXX * halfDiagonal * halfDiagonal + tangentXH * halfDiagonal * std::max(0.0, high - low));
    return cell;
}

CurvedJacobian curvedJacobian(const EarthShape& e, const CurvedCell& cell) {
    CurvedJacobian j;
    if (e.kind == EarthKind::Flat) return j;
    const glm::dvec3& c = cell.flatCenter;
    const double r = cell.flatRadius;
    // The horizontal columns by central differences a metre apart (the map's second derivative
    // is under 1 / R: the error is some 1e-14).
    j.east = 0.5 * (curvedPosition(e, c.x + 1.0, c.y, c.z) - curvedPosition(e, c.x - 1.0, c.y, c.z));
    j.south = 0.5 * (curvedPosition(e, c.x, c.y, c.z + 1.0) - curvedPosition(e, c.x, c.y, c.z - 1.0));
    // Their lengths change with the height ((R + h) / R), on the sphere with the distance from
    // the origin (sin(d / R) / (d / R) across the radius), and on the ellipsoid with the latitude
    // (cos(latitude) east, the meridian's radius M south: |dM / M dphi| < 0.011 / 0.99).
    const double heights = cell.heightSpan + 2.0 * r;
    if (e.kind == EarthKind::Sphere) {
        const double farthest = std::hypot(c.x - e.originX, c.z - e.originZ) + r;
        j.stretchChange = heights / e.radius + 2.0 * r * farthest / (e.radius * e.radius);
        return j;
    }
    const double latitudes = 2.0 * r / e.metresPerRadianZ; // the flat sphere's span of latitude, radians
    const double edge = std::abs(e.latitude0 - (c.z - e.originZ) / e.metresPerRadianZ) + 0.5 * latitudes;
    // Within 4° of a pole the east column's length changes too fast to say anything.
    j.stretchChange = edge >= 1.5 ? 1e9 : heights / (0.99 * kWgs84A) + latitudes * (std::tan(edge) + 0.012);
    return j;
}

} // namespace hexlod
