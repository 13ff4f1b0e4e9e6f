// The checks of what the C ABI accepts (hexlod_inputs.h): cameras for the criteria of paper §5,
// settings of the refinement (§5, §6) and of the blends and stream (§7).
#include "api/hexlod_inputs.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

#include <glm/geometric.hpp>

#include "stream/geomorph.h"

namespace hexlod::api {

namespace {

// hexlod_last_error() points here until the next refusal (the ABI's messages are static storage).
thread_local char message[320];

__attribute__((format(printf, 1, 2))) const char* refuse(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(message, sizeof(message), format, args);
    va_end(args);
    return message;
}

bool within(double value, double low, double high) { return value >= low && value <= high; } // false for NaN

// Zero means the default; anything else must lie in [low, high].
bool zeroOrWithin(double value, double low, double high) { return value == 0.0 || within(value, low, high); }

const char* checkPoint(const char* name, const double* p) {
    for (int k = 0; k < 3; ++k)
        if (!within(p[k], -kMaxLengthM, kMaxLengthM))
            return refuse("degenerate camera: %s[%d] is %g; it must be a finite number of metres from -1e12 to 1e12", name, k, p[k]);
    return nullptr;
}

} // namespace

const char* checkCamera(const hexlod_camera& c, glm::dvec3* up) {
    if (const char* error = checkPoint("eye", c.eye)) return error;
    if (const char* error = checkPoint("target", c.target)) return error;
    if (const char* error = checkPoint("up", c.up)) return error;
    if (!within(c.tan_half_fov_y, kMinTanHalfFov, kMaxTanHalfFov))
        return refuse("degenerate camera: tan_half_fov_y is %g; it must be a finite number from 0.0001 to 10000 "
                      "(a vertical field of view from 0.0115 to 179.989 degrees)", c.tan_half_fov_y);
    if (!within(c.aspect, kMinAspect, kMaxAspect))
        return refuse("degenerate camera: aspect is %g; it must be a finite width / height ratio from 0.0001 to 10000", c.aspect);
    if (!within(c.viewport_height_px, kMinViewportPx, kMaxViewportPx))
        return refuse("degenerate camera: viewport_height_px is %g; it must be a finite number of device pixels from 1 to 100000",
                      c.viewport_height_px);
    if (!within(c.far_m, kMinNearM, kMaxLengthM))
        return refuse("degenerate camera: far_m is %g; it must be a finite number of metres from 1e-6 to 1e12", c.far_m);
    if (!within(c.near_m, kMinNearM, kMaxLengthM) || !(c.near_m < c.far_m))
        return refuse("degenerate camera: near_m is %g; it must be a finite number of metres from 1e-6 to less than far_m (%g)",
                      c.near_m, c.far_m);
    const glm::dvec3 eye(c.eye[0], c.eye[1], c.eye[2]), target(c.target[0], c.target[1], c.target[2]);
    const double distance = glm::length(target - eye);
    if (!(distance >= kMinLookDistanceM))
        return refuse("degenerate camera: target is %g m from eye; it must be at least 1e-6 m away (eye on the target)", distance);
    const glm::dvec3 given(c.up[0], c.up[1], c.up[2]);
    const double upLength = glm::length(given);
    if (upLength == 0.0) {
        *up = glm::dvec3(0, 1, 0);
    } else if (!(upLength >= kMinUpLength)) {
        return refuse("degenerate camera: up is (%g, %g, %g); give (0, 0, 0) for +y or a vector at least 1e-6 long", c.up[0], c.up[1],
                      c.up[2]);
    } else {
        *up = given / upLength;
    }
    const double sine = glm::length(glm::cross((target - eye) / distance, *up));
    if (!(sine >= kMinUpSine))
        return refuse("degenerate camera: up (%g, %g, %g) is along the view direction; looking straight up or down, give an up "
                      "off the view, e.g. (0, 0, -1) for north at the top", up->x, up->y, up->z);
    return nullptr;
}

const char* checkSettings(const hexlod_settings& s) {
    if (!zeroOrWithin(s.tau_px, kMinTauPx, kMaxTauPx))
        return refuse("settings: tau_px is %g; tau must be a positive number of pixels from 0.01 to 10000 (0: 1 px)", s.tau_px);
    if (!zeroOrWithin(s.max_error_m, kMinMaxErrorM, kMaxMaxErrorM))
        return refuse("settings: max_error_m is %g; the maximum error must be a positive number of metres from 1e-6 to 1e9 "
                      "(0: tau mode)", s.max_error_m);
    if (!zeroOrWithin(s.vertical_scale, kMinVerticalScale, kMaxVerticalScale))
        return refuse("settings: vertical_scale is %g; the vertical scale must be a positive number from 0.001 to 1000 (0: 1)",
                      s.vertical_scale);
    if (!within(s.budget_ms, 0.0, kMaxBudgetMs))
        return refuse("settings: budget_ms is %g; the time budget must be a number of milliseconds from 0 (no limit) to 60000",
                      s.budget_ms);
    if (s.max_operations < 0)
        return refuse("settings: max_operations is %d; it must be 0 (no limit) or a positive number of operations", s.max_operations);
    if (s.max_triangles < 0)
        return refuse("settings: max_triangles is %d; it must be 0 (no cap) or a positive number of triangles", s.max_triangles);
    if (s.morph_frames < 0 || s.morph_frames > Geomorph::kMaxFrames)
        return refuse("settings: morph_frames is %d; morph frames must be 0 (off) to 1000", s.morph_frames);
    if (s.layout != HEXLOD_LAYOUT_FANS && s.layout != HEXLOD_LAYOUT_TRIANGLES)
        return refuse("settings: layout is %d; unknown index layout (expected 0 = fans, 1 = triangles)", s.layout);
    return nullptr;
}

const char* checkEarth(int32_t kind, double originX, double originZ, double radius, double latitude0, double perRadianX,
                       double perRadianZ, EarthShape& earth) {
    if (kind != HEXLOD_EARTH_FLAT && kind != HEXLOD_EARTH_SPHERE && kind != HEXLOD_EARTH_GEOGRAPHIC)
        return refuse("earth: kind is %d; unknown shape (expected 0 = flat, 1 = sphere, 2 = geographic)", kind);
    EarthShape e;
    e.kind = EarthKind(kind);
    if (kind == HEXLOD_EARTH_FLAT) {
        earth = e;
        return nullptr;
    }
    if (!within(originX, -1e12, 1e12) || !within(originZ, -1e12, 1e12))
        return refuse("earth: the origin is (%g, %g); each coordinate must be a number of metres from -1e12 to 1e12", originX, originZ);
    e.originX = originX, e.originZ = originZ;
    if (kind == HEXLOD_EARTH_SPHERE) {
        if (!within(radius, 1e3, 1e9)) return refuse("earth: radius_m is %g; a sphere's radius must be 1e3 to 1e9 metres", radius);
        e.radius = radius;
    } else {
        if (!within(latitude0, -1.5707963267948966, 1.5707963267948966))
            return refuse("earth: latitude0_rad is %g; the origin's latitude must be -pi/2 to pi/2 radians", latitude0);
        if (!within(perRadianX, 1.0, 1e12) || !within(perRadianZ, 1.0, 1e12))
            return refuse("earth: metres per radian are %g east and %g south; each must be 1 to 1e12", perRadianX, perRadianZ);
        e.latitude0 = latitude0, e.metresPerRadianX = perRadianX, e.metresPerRadianZ = perRadianZ;
    }
    earth = e;
    return nullptr;
}

} // namespace hexlod::api
