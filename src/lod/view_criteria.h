// Refinement criteria (paper §5, after Hoppe 1997), made conservative: a bound, not an
// estimate, on how far any sample under a cell can appear from the drawn surface on screen.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

#include "lod/cell_bounds.h"
#include "lod/earth_shape.h"

namespace hexlod {

/// A perspective camera in the world frame (x east, y up, z south; metres, heights already
/// times the vertical scale).
struct View {
    glm::dvec3 eye{0.0};
    glm::dvec3 right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, -1}; // orthonormal view basis
    double tanHalfX = 1.0, tanHalfY = 1.0; // frustum half-angle tangents
    double pixelsPerTangent = 540.0;       // viewport height in pixels / (2 tan(fovy / 2))
    double nearPlane = 1.0, farPlane = 1e12; // metres
};

/// Builds a view from eye, target and up. Returns false for a degenerate camera (eye on the
/// target, up along the view direction, non-positive sizes or planes).
bool makeView(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double tanHalfFovY,
              double aspect, double viewportHeightPx, double nearPlane, double farPlane, View& view);

/// The cell's bounding sphere: its footprint box, heights from `low` to `high` (times the
/// vertical scale).
void boundingSphere(const Footprint& f, const CellError& e, double verticalScale, glm::dvec3& center, double& radius);

/// Whether the sphere lies completely outside one plane of the view frustum (§5, first test).
bool outsideFrustum(const View& view, const glm::dvec3& center, double radius);

/// Whether every point of the sphere sees the back of every surface with a slope in the box
/// (§5, second test, made a bound): the normals (-s*dx, 1, -s*dz) for the vertical scale s
/// all satisfy (p - eye) . n > 0 for every point p of the sphere. Such a cell's samples
/// cannot be seen: where a ray from an eye above a height field first meets it, the surface
/// faces the eye. back: how far the eye may move while the cell stays back-facing; front (when
/// it is not): how far before it may turn its back (infinite where nothing can be told).
struct BackFaces {
    bool backFacing = false;
    double back = 0.0, front = 0.0; // metres
};
BackFaces backFaces(const View& view, const glm::dvec3& center, double radius, const SlopeBox& slopes, double verticalScale);

/// The same test on the curved Earth (earth_shape.h): each slope's normal drawn through the
/// map's Jacobian at the cell's centre (curvedJacobian's east and south, and curved.up; the
/// normal is linear in the slope, so the corners of the box still bound it), then allowed to
/// turn by the frame's turn over the cell (curved.tilt) and the stretch's change times the steepest slope:
/// a unit normal m within angle a of n gives (p - eye) . m >= cos(a) (p - eye) . n - sin(a) |p - eye|.
BackFaces curvedBackFaces(const View& view, const EarthShape& earth, const CurvedCell& curved, const SlopeBox& slopes, double verticalScale);

/// Upper bound, in pixels, of the screen distance between any sample under the cell and the
/// drawn surface above or below it (§5, third test, made a bound):
///   a vertical segment of length e = error * verticalScale inside the sphere projects to at
///   most pixelsPerTangent * e * g / Zmin pixels, where Zmin is the sphere's nearest depth
///   (depth minus radius, at least the near plane or `nearest`) and g the largest length of the projected
///   up vector over the sphere's range of screen tangents (1 looking level, 0 looking straight
///   down at the cell's centre): the projection's Jacobian applied to the world's up vector.
/// `nearest`: the smallest depth Zmin may take (the view's near plane unless given).
double projectedErrorPixels(const View& view, const glm::dvec3& center, double radius, double verticalError);
double projectedErrorPixels(const View& view, const glm::dvec3& center, double radius, double verticalError, double nearest);

/// The same bound on the curved Earth (earth_shape.h): `curved` gives the sphere, the cell's up
/// vector in place of the world's, how far that turns over the cell (its share is the turn
/// times the largest projected length of a unit vector), the sag added to the error, and the
/// drift, a displacement in any direction.
double projectedErrorPixels(const View& view, const CurvedCell& curved, double verticalError, double nearest);

/// A cell's bound on the curved Earth (earth_shape.h) from its footprint and cached bound:
/// its flat bounding sphere (boundingSphere) drawn on `earth`.
CurvedCell curvedCellOf(const EarthShape& earth, const Footprint& f, const CellError& e, double verticalScale);

/// The largest length of the projection's Jacobian (times depth) applied to a unit vector, for
/// screen tangents up to tMax2 = tx^2 + ty^2: |(vx - tx vz, vy - ty vz)| <= sqrt(2 (1 + tMax2)).
inline double anyDirectionGain(double tMax2) { return std::sqrt(2.0 * (1.0 + tMax2)); }

} // namespace hexlod
