#version 300 es
// The sky behind the terrain from the same scattering model as the terrain (Hoffman &
// Preetham 2002, paper §7): the in-scattered light of the whole air column along the view
// ray, the sun's disc, and below the horizon (past the field) the haze over a dark ground.
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
    // The air is lit by sunlight of a height above the eye: most scattering happens there.
    scatter(depthR, depthM, cosTheta, sunlightAt(eye + 2000.0), extinction, inscatter);
    vec3 sunlight = sunlightAt(eye);
    // The sun's disc, about half a degree across.
    float disc = smoothstep(0.99996, 0.99999, cosTheta);
    vec3 background = sunlight * disc * 40.0;
    // Below the horizon: a dark ground in sunlight, seen through the haze.
    float below = smoothstep(0.0, -0.03, dir.y);
    background = mix(background, vec3(0.03, 0.035, 0.04) * sunlight * max(uSunDirection.y, 0.0), below);
    outColor = vec4(toneMap(background * extinction + inscatter), 1.0);
}
