// A camera's view from a position and a heading, for the tests of what the camera moving does
// to margins (camera_odometers_test, sweep_summaries_test).
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "lod/view_criteria.h"

namespace hexlod::test {

/// Looking along `yaw` (radians from -z towards +x) and down by `pitch`, 16:9, 60 degrees
/// vertical field of view.
inline View viewAt(const glm::dvec3& eye, double yaw, double pitch) {
    View v;
    v.eye = eye;
    v.forward = {std::cos(pitch) * std::sin(yaw), -std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
    v.right = glm::normalize(glm::cross(v.forward, glm::dvec3(0, 1, 0)));
    v.up = glm::cross(v.right, v.forward);
    v.tanHalfY = 0.57735026918962573;
    v.tanHalfX = v.tanHalfY * 16.0 / 9.0;
    return v;
}

} // namespace hexlod::test
