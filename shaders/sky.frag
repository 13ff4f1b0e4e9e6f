#version 300 es
// The sky behind the terrain from the same scattering model as the terrain (Hoffman &
// Preetham 2002, paper §7): the in-scattered light of the whole air column along the view
// ray and the sun's disc. Below the horizon, past the field's edges, the Earth goes on as
// plain ground at the field's lowest height, lit and hazed as the terrain is, to the horizon:
// a plane, or on the curved Earth (earth.glsl) a sphere, whose horizon dips below eye level.
precision highp float;

in vec3 vFar;

uniform vec3 uCameraPosition; // drawn metres
uniform float uEyeHeight;     // the eye's height above the surface's zero, true metres
uniform vec3 uEyeUp;          // the surface's up under the eye (on the curved Earth)
uniform float uVerticalScale;
uniform float uGroundLevel;   // drawn metres of the plain ground (-1e30: none)
uniform vec3 uSkyLight;       // the sky's light on level ground

#include "scattering.glsl"
#include "ground_color.glsl"
#include "tonemap.glsl"
#include "earth.glsl"

out vec4 outColor;

// The plain ground where the view ray meets it, at drawn distance t along dir; up: the
// ground's up there.
vec4 plainGround(vec3 dir, float t, float eye, vec3 up) {
    vec3 ray = dir * t;
    vec3 p = uCameraPosition + ray;
    float h = uGroundLevel / uVerticalScale;
    // The air is not exaggerated: optical depths follow the ray in true metres (as terrain.vert).
    float s = uEarthKind == 0 ? length(vec3(ray.x, ray.y / uVerticalScale, ray.z)) : t;
    vec3 extinction, inscatter;
    scatter(airPath(eye, h, s, uScaleHeight.x), airPath(eye, h, s, uScaleHeight.y), dot(dir, uSunDirection),
        sunlightAt(0.5 * (eye + h)), extinction, inscatter);
    vec3 albedo = naturalGround(h, 0.0, groundNoise(p.xz));
    vec3 radiance = albedo * (sunlightAt(h) * max(dot(uSunDirection, up), 0.0) + uSkyLight);
    return vec4(toneMap(radiance * extinction + inscatter), 1.0);
}

// On the curved Earth: the distance along dir to the ground, a sphere of the Earth's radius
// tangent to the surface under the eye at the ground level, or -1 past its horizon. In the
// form that loses nothing to float: no squares of the Earth's radius are subtracted.
float curvedGroundDistance(vec3 dir) {
    float groundRadius = uEarthRadius + uGroundLevel;
    float above = uEyeHeight * uVerticalScale - uGroundLevel; // drawn metres over the plain ground
    float mu = dot(dir, uEyeUp), r = groundRadius + above;
    if (above <= 0.0 || mu >= 0.0) return -1.0;
    float disc = r * r * mu * mu - above * (2.0 * groundRadius + above);
    if (disc < 0.0) return -1.0;
    return above * (2.0 * groundRadius + above) / (-r * mu + sqrt(disc));
}

// Optical depth (metres of sea-level air) of a level ray through the whole air, both ways from
// its lowest height h, for scale height H: the Chapman function's horizontal limit,
// 2 H exp(-h / H) sqrt(pi (R + h) / (2 H)).
float limbDepth(float h, float H) {
    return 2.0 * H * exp(-h / H) * sqrt(PI * (uEarthRadius + h) / (2.0 * H));
}

void main() {
    vec3 dir = normalize(vFar - uCameraPosition);
    float eye = max(uEyeHeight, 0.0);
    // Up at the eye: the frame's on the plane, the sphere's on the curved Earth.
    vec3 eyeUp = uEarthKind == 0 ? vec3(0.0, 1.0, 0.0) : uEyeUp;
    float elevation = dot(dir, eyeUp);
    if (uEarthKind == 0) {
        if (dir.y < 0.0 && uCameraPosition.y > uGroundLevel) {
            outColor = plainGround(dir, (uCameraPosition.y - uGroundLevel) / -dir.y, eye, eyeUp);
            return;
        }
    } else if (uGroundLevel > -1e29) {
        float t = curvedGroundDistance(dir);
        if (t > 0.0) {
            // The ground's up there: from the sphere's centre, (R + eye height) below the eye.
            vec3 fromCentre = dir * t + eyeUp * (uEarthRadius + uEyeHeight * uVerticalScale);
            outColor = plainGround(dir, t, eye, normalize(fromCentre));
            return;
        }
    }
    float mass = airMass(max(elevation, 0.0));
    float depthR = uScaleHeight.x * exp(-eye / uScaleHeight.x) * mass;
    float depthM = uScaleHeight.y * exp(-eye / uScaleHeight.y) * mass;
    float cosTheta = dot(dir, uSunDirection);
    vec3 extinction, inscatter;
    // Where the light is scattered: rays towards the horizon run through low, dense air (on the
    // curved Earth they pass below the eye), rays upwards through the air around the eye. The
    // sunlight there is reddened accordingly when the sun is low.
    float mu = sqrt(max(elevation, 0.0));
    float scatteredAt = mix(0.5 * eye, eye + 1000.0, mu);
    if (uEarthKind != 0 && elevation < 0.0) {
        // Below eye level past the Earth's limb: the ray dips to its lowest height and rises
        // out again, through the air of both halves (the limb's bright haze seen from high up).
        float lowest = max(eye - (uEarthRadius + eye) * elevation * elevation / (1.0 + sqrt(1.0 - elevation * elevation)), 0.0);
        depthR = limbDepth(lowest, uScaleHeight.x) - uScaleHeight.x * exp(-eye / uScaleHeight.x) * airMass(-elevation);
        depthM = limbDepth(lowest, uScaleHeight.y) - uScaleHeight.y * exp(-eye / uScaleHeight.y) * airMass(-elevation);
        scatteredAt = lowest + 1000.0;
    }
    scatter(depthR, depthM, cosTheta, sunlightAt(scatteredAt), extinction, inscatter);
    // The sun's disc, about half a degree across, above the horizon. Below the horizon (past
    // the field) only the haze: from high up, space is black.
    float disc = smoothstep(0.99996, 0.99999, cosTheta) * smoothstep(-0.01, 0.0, elevation);
    vec3 background = sunlightAt(eye) * disc * 40.0;
    outColor = vec4(toneMap(background * extinction + inscatter), 1.0);
}
