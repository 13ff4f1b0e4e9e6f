// What the C ABI accepts (api/hexlod.h): every number a caller passes in a camera or in the
// settings is checked here before anything changes, so a refused call keeps the previous camera
// and settings. Each refusal names the struct field, the value given and what is allowed.
// Not a public header; the limits are those hexlod.h documents.
#pragma once

#include <glm/vec3.hpp>

#include "api/hexlod.h"
#include "lod/earth_shape.h"

namespace hexlod::api {

// The limits: wide enough for any real view (a camera a billion km out, a 0.01 degree
// telephoto, a capture 100 000 pixels high), narrow enough that every product and square of
// the criteria (§5) stays finite and means something. NaN and infinities are never accepted.
constexpr double kMaxLengthM = 1e12;                          // |eye|, |target| components, far
constexpr double kMinLookDistanceM = 1e-6;                    // |target - eye|
constexpr double kMinUpLength = 1e-6;                         // a non-zero up, before normalising
constexpr double kMinUpSine = 1e-6;                           // sine of the angle between up and the view
constexpr double kMinTanHalfFov = 1e-4, kMaxTanHalfFov = 1e4; // 0.0115 to 179.989 degrees
constexpr double kMinAspect = 1e-4, kMaxAspect = 1e4;
constexpr double kMinViewportPx = 1.0, kMaxViewportPx = 1e5;
constexpr double kMinNearM = 1e-6;
constexpr double kMinTauPx = 0.01, kMaxTauPx = 1e4;
constexpr double kMinMaxErrorM = 1e-6, kMaxMaxErrorM = 1e9; // below a float32 height's resolution means nothing
constexpr double kMinVerticalScale = 1e-3, kMaxVerticalScale = 1e3;
constexpr double kMaxBudgetMs = 60000.0;

/// Null when the camera is acceptable (and *up is its up vector, normalised: +y for (0, 0, 0)),
/// else the refusal, starting "degenerate camera: ".
const char* checkCamera(const hexlod_camera& camera, glm::dvec3* up);

/// Null when the settings are acceptable, else the refusal, starting "settings: ".
const char* checkSettings(const hexlod_settings& settings);

/// hexlod_terrain_set_earth's numbers as an EarthShape, or why they are refused (earth untouched).
const char* checkEarth(int32_t kind, double originX, double originZ, double radius, double latitude0, double perRadianX,
                       double perRadianZ, EarthShape& earth);

} // namespace hexlod::api
