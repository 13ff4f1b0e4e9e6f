// The curved Earth: where a flat point is drawn, as the core bounds it (src/lod/earth_shape.h,
// the same shapes; web/geo/earth_shape.js sets these uniforms). The frame is fixed: east, up
// and south metres of the tangent frame at the origin. The formulas are arranged so that no
// two large numbers are subtracted: float keeps centimetres near the origin.

uniform highp int uEarthKind;  // 0 flat, 1 sphere, 2 geographic (WGS 84)
uniform vec2 uEarthOrigin;     // flat metres (x, z) drawn at the frame's origin
uniform float uEarthRadius;    // sphere: metres; geographic: the origin's mean radius (for the sky)
uniform vec3 uEarthGeographic; // geographic: the origin's latitude (radians), flat metres per radian east and south

const float WGS84_A = 6378137.0;
const float WGS84_E2 = 6.69437999014e-3;

// The sphere: the offset d from the origin along the great circle in its direction; a the
// angle d / R, u the direction.
void sphereFrame(vec2 d, out float a, out vec2 u) {
    float dist = length(d);
    a = dist / uEarthRadius;
    u = dist > 0.0 ? d / dist : vec2(1.0, 0.0);
}

// Geographic: the latitude and longitude offsets of a flat offset, and the origin's latitude.
void geographicAngles(vec2 d, out float phi0, out float dPhi, out float dLambda) {
    phi0 = uEarthGeographic.x;
    dPhi = -d.y / uEarthGeographic.z;
    dLambda = d.x / uEarthGeographic.y;
}

// A vector given in the Earth-centred frame turned to the origin's meridian (x towards the
// origin's meridian at the equator, z the axis) as east, up, south of the origin.
vec3 fromMeridianFrame(vec3 v, float phi0) {
    float s0 = sin(phi0), c0 = cos(phi0);
    return vec3(v.y, c0 * v.x + s0 * v.z, s0 * v.x - c0 * v.z);
}

/**
 * Where the flat offset d (metres east and south) from a ground point drawn at the frame's origin,
 * at height h (times the exaggeration), is drawn: in the tangent frame at that point (east, up,
 * south metres). phi0: the point's latitude (geographic). The sphere's wrap keeps the distances
 * and directions from the field's centre, so its d is always from there.
 */
vec3 earthOffset(vec2 d, float h, float phi0) {
    if (uEarthKind == 0) return vec3(d.x, h, d.y);
    if (uEarthKind == 1) {
        float a;
        vec2 u;
        sphereFrame(d, a, u);
        float R = uEarthRadius, s = sin(0.5 * a);
        float along = (R + h) * sin(a);
        return vec3(along * u.x, h - 2.0 * (R + h) * s * s, along * u.y);
    }
    float dPhi = -d.y / uEarthGeographic.z, dLambda = d.x / uEarthGeographic.y;
    float phi = phi0 + dPhi;
    float sPhi = sin(phi), cPhi = cos(phi), s0 = sin(phi0);
    float w = sqrt(1.0 - WGS84_E2 * sPhi * sPhi), w0 = sqrt(1.0 - WGS84_E2 * s0 * s0);
    float n = WGS84_A / w, n0 = WGS84_A / w0;
    float halfDPhi = sin(0.5 * dPhi), halfDLambda = sin(0.5 * dLambda);
    float sinDiff = 2.0 * cos(phi0 + 0.5 * dPhi) * halfDPhi;  // sin(phi) - sin(phi0)
    float cosDiff = -2.0 * sin(phi0 + 0.5 * dPhi) * halfDPhi; // cos(phi) - cos(phi0)
    float nDiff = WGS84_A * WGS84_E2 * sinDiff * (sPhi + s0) / (w * w0 * (w + w0)); // N - N0
    // Earth-centred, minus the origin, with the origin's meridian as longitude 0.
    float dx = nDiff * cPhi + h * cPhi + n0 * cosDiff - 2.0 * (n + h) * cPhi * halfDLambda * halfDLambda;
    float dy = (n + h) * cPhi * sin(dLambda);
    float dz = (1.0 - WGS84_E2) * (nDiff * sPhi + n0 * sinDiff) + h * sPhi;
    return fromMeridianFrame(vec3(dx, dy, dz), phi0);
}

/** The drawn position of flat p = (x, height, z), the height already times the exaggeration. */
vec3 earthPosition(vec3 p) {
    if (uEarthKind == 0) return p;
    return earthOffset(p.xz - uEarthOrigin, p.y, uEarthGeographic.x);
}

/** The drawn frame's east, up and south at flat (x, z), each a unit vector. */
void earthFrame(vec2 xz, out vec3 east, out vec3 up, out vec3 south) {
    east = vec3(1.0, 0.0, 0.0), up = vec3(0.0, 1.0, 0.0), south = vec3(0.0, 0.0, 1.0);
    if (uEarthKind == 0) return;
    vec2 d = xz - uEarthOrigin;
    if (uEarthKind == 1) {
        float a;
        vec2 u;
        sphereFrame(d, a, u);
        vec3 radial = vec3(cos(a) * u.x, -sin(a), cos(a) * u.y); // away from the origin, along the surface
        vec3 around = vec3(-u.y, 0.0, u.x);
        up = vec3(sin(a) * u.x, cos(a), sin(a) * u.y);
        east = u.x * radial - u.y * around;
        south = u.y * radial + u.x * around;
        return;
    }
    float phi0, dPhi, dLambda;
    geographicAngles(d, phi0, dPhi, dLambda);
    float phi = phi0 + dPhi, sPhi = sin(phi), cPhi = cos(phi), sL = sin(dLambda), cL = cos(dLambda);
    east = fromMeridianFrame(vec3(-sL, cL, 0.0), phi0);
    up = fromMeridianFrame(vec3(cPhi * cL, cPhi * sL, sPhi), phi0);
    south = -fromMeridianFrame(vec3(-sPhi * cL, -sPhi * sL, cPhi), phi0);
}

/** How many drawn metres a flat metre east and south is at flat (x, z) (1 but for geographic grids). */
vec2 earthStretch(vec2 xz) {
    if (uEarthKind != 2) return vec2(1.0);
    vec2 d = xz - uEarthOrigin;
    float phi = uEarthGeographic.x - d.y / uEarthGeographic.z, s = sin(phi);
    float w = sqrt(1.0 - WGS84_E2 * s * s);
    return vec2(WGS84_A / w * cos(phi) / uEarthGeographic.y, WGS84_A * (1.0 - WGS84_E2) / (w * w * w) / uEarthGeographic.z);
}

/** A flat normal (x east, y up, z south) at flat (x, z) as a drawn one. */
vec3 earthNormal(vec2 xz, vec3 n) {
    if (uEarthKind == 0) return n;
    vec3 east, up, south;
    earthFrame(xz, east, up, south);
    vec2 stretch = earthStretch(xz);
    return n.x / stretch.x * east + n.y * up + n.z / stretch.y * south;
}
