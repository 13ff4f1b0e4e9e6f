#version 300 es
// The sky behind the terrain from the same scattering model as the terrain (Hoffman &
// Preetham 2002, paper §7): the in-scattered light of the whole air column along the view
// ray and the sun's disc.
precision highp float;

in vec3 vFar;

uniform vec3 uCameraPosition; // drawn metres
uniform float uVerticalScale;

#include "scattering.glsl"
#include "tonemap.glsl"

out vec4 outColor;

void main() {
    vec3 dir = normalize(vFar - uCameraPosition);
    float eye = max(uCameraPosition.y / uVerticalScale, 0.0);
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
