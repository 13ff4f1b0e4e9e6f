#version 300 es
// The sky behind the terrain from the same scattering model as the terrain (Hoffman &
// Preetham 2002, paper §7): the in-scattered light of the whole air column along the view
// ray and the sun's disc. Below the horizon, past the field's edges, the Earth goes on as
// plain ground at the field's lowest height, lit and hazed as the terrain is, to the horizon.
precision highp float;

in vec3 vFar;

uniform vec3 uCameraPosition; // drawn metres
uniform float uVerticalScale;
uniform float uGroundLevel;   // drawn metres of the plain ground (-1e30: none)
uniform vec3 uSkyLight;       // the sky's light on level ground

#include "scattering.glsl"
#include "ground_color.glsl"
#include "tonemap.glsl"

out vec4 outColor;

// The plain ground where the view ray meets it, at drawn distance t along dir.
vec4 plainGround(vec3 dir, float t, float eye) {
    vec3 ray = dir * t;
    vec3 p = uCameraPosition + ray;
    float h = uGroundLevel / uVerticalScale;
    // The air is not exaggerated: optical depths follow the ray in true metres (as terrain.vert).
    float s = length(vec3(ray.x, ray.y / uVerticalScale, ray.z));
    vec3 extinction, inscatter;
    scatter(airPath(eye, h, s, uScaleHeight.x), airPath(eye, h, s, uScaleHeight.y), dot(dir, uSunDirection),
        sunlightAt(0.5 * (eye + h)), extinction, inscatter);
    vec3 albedo = naturalGround(h, 0.0, groundNoise(p.xz));
    vec3 radiance = albedo * (sunlightAt(h) * max(uSunDirection.y, 0.0) + uSkyLight);
    return vec4(toneMap(radiance * extinction + inscatter), 1.0);
}

void main() {
    vec3 dir = normalize(vFar - uCameraPosition);
    float eye = max(uCameraPosition.y / uVerticalScale, 0.0);
    if (dir.y < 0.0 && uCameraPosition.y > uGroundLevel) {
        outColor = plainGround(dir, (uCameraPosition.y - uGroundLevel) / -dir.y, eye);
        return;
    }
    float mass = airMass(max(dir.y, 0.0));
    float depthR = uScaleHeight.x * exp(-eye / uScaleHeight.x) * mass;
    float depthM = uScaleHeight.y * exp(-eye / uScaleHeight.y) * mass;
    float cosTheta = dot(dir, uSunDirection);
    vec3 extinction, inscatter;
    // Where the light is scattered: rays towards the horizon run through low, dense air (on the
    // curved Earth they pass below the eye), rays upwards through the air around the eye. The
    // sunlight there is reddened accordingly when the sun is low.
    float mu = sqrt(max(dir.y, 0.0));
    scatter(depthR, depthM, cosTheta, sunlightAt(mix(0.5 * eye, eye + 1000.0, mu)), extinction, inscatter);
    // The sun's disc, about half a degree across, above the horizon. Below the horizon (past
    // the field) only the haze: from high up, space is black.
    float disc = smoothstep(0.99996, 0.99999, cosTheta) * smoothstep(-0.01, 0.0, dir.y);
    vec3 background = sunlightAt(eye) * disc * 40.0;
    outColor = vec4(toneMap(background * extinction + inscatter), 1.0);
}
