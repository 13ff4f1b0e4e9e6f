// The curved Earth under a georeferenced field: where a flat position (x east, height, z south,
// metres from the first sample) is drawn, and what that does to a cell's bound (paper §5).
//
// The drawn frame is fixed: east, up and south metres of a tangent frame at an origin on the
// surface, so the curved world does not move with the camera and the refiner's margins stay
// valid as they are. Two shapes:
// - Sphere: a projected (or unreferenced) plane wrapped onto a sphere of one radius, keeping
//   distances and directions from the origin (an azimuthal equidistant wrap; a projected CRS is
//   itself near-conformal, so this is within its own distortion of the true places).
// - Geographic: columns are longitudes and rows latitudes at fixed steps, placed on the WGS 84
//   ellipsoid exactly, so east-west spacing follows the cosine of each row's latitude.
// Heights stand along the surface normal in both. shaders/earth.glsl draws the same shapes.
//
// A cell's bound (CurvedCell) is what §5's test needs to stay a bound on the curved surface:
// the flat bounding sphere's image, the cell's up vector and how far it turns, and the chord
// error: the drawn triangles join curved vertices with straight edges, so they lie off the
// curved surface by up to the sag.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace hexlod {

enum class EarthKind : int32_t { Flat = 0, Sphere = 1, Geographic = 2 };

struct EarthShape {
    EarthKind kind = EarthKind::Flat;
    double originX = 0.0, originZ = 0.0; // flat metres drawn at the frame's origin (height 0 there is (0, 0, 0))
    double radius = 6371008.8;           // Sphere: metres
    double latitude0 = 0.0;              // Geographic: radians at the origin
    double metresPerRadianX = 1.0;       // Geographic: flat x metres per radian of longitude (> 0)
    double metresPerRadianZ = 1.0;       // Geographic: flat z metres per radian of latitude, southwards (> 0)

    bool flat() const { return kind == EarthKind::Flat; }
    friend bool operator==(const EarthShape& a, const EarthShape& b) {
        return a.kind == b.kind && a.originX == b.originX && a.originZ == b.originZ && a.radius == b.radius &&
               a.latitude0 == b.latitude0 && a.metresPerRadianX == b.metresPerRadianX && a.metresPerRadianZ == b.metresPerRadianZ;
    }
    friend bool operator!=(const EarthShape& a, const EarthShape& b) { return !(a == b); }
};

/// WGS 84.
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84E2 = 6.69437999014132e-3; // first eccentricity squared, f (2 - f) with f = 1 / 298.257223563

/// Where the flat point (x, h, z) is drawn (h already times the vertical scale). Flat: itself.
glm::dvec3 curvedPosition(const EarthShape& earth, double x, double h, double z);

/// The surface normal (unit, drawn frame) under the flat point (x, z).
glm::dvec3 curvedUp(const EarthShape& earth, double x, double z);

/// A cell's bound on the curved surface, from its flat bounding sphere (centre, radius; heights
/// times the vertical scale) and height range (low, high, times the vertical scale):
/// - every point of the flat sphere is drawn within `radius` of `center`;
/// - a sample e above or below the flat surface is drawn e along the normal there, which is
///   within `tilt` radians of `up`;
/// - the drawn triangles lie off the curved image of the flat ones by at most `sag` metres
///   along the normal and `drift` metres across it.
struct CurvedCell {
    glm::dvec3 center{0.0};
    double radius = 0.0;
    glm::dvec3 up{0.0, 1.0, 0.0};
    double tilt = 0.0;  // radians
    double sag = 0.0;   // metres, along the normal (a chord under its arc)
    double drift = 0.0; // metres, in any direction (the map's bending within the surface)
    // The flat sphere and height span it was made from (for curvedJacobian, which only the
    // back-face test needs).
    glm::dvec3 flatCenter{0.0};
    double flatRadius = 0.0, heightSpan = 0.0;
};

/// The map's Jacobian at a cell's flat centre: drawn metres per flat metre east and south (the
/// third column is the cell's `up`), and how much their lengths change over the cell's flat
/// sphere, relative (a slope's drawn normal turns by up to that times the slope).
struct CurvedJacobian {
    glm::dvec3 east{1.0, 0.0, 0.0}, south{0.0, 0.0, 1.0};
    double stretchChange = 0.0;
};
CurvedJacobian curvedJacobian(const EarthShape& earth, const CurvedCell& cell);

CurvedCell curvedCell(const EarthShape& earth, const glm::dvec3& flatCenter, double flatRadius, double halfDiagonal,
                      double low, double high);

} // namespace hexlod
