#version 300 es
// Terrain fragment stage (paper §7): normals from the full-resolution field (or the mesh's,
// averaged from the adjacent triangles), procedural ground colour from height, slope and
// per-pixel noise, the sun with terrain shadows, sky light modulated by the 8-bit ambient
// occlusion, the atmosphere's extinction and in-scattering from the vertex stage, and tone
// mapping. Analysis modes: hypsometric tint, slope classes, hillshade; "plain" is the former
// Lambert shading with the mesh's normals (a baseline for frame times).
precision highp float;
precision highp sampler2DArray;

in vec3 vNormal;
in vec3 vWorld;
in float vHeight;
in vec3 vExtinction;
in vec3 vInscatter;
in vec3 vSunlight;
in vec3 vSunLocal;
in vec3 vToEyeLocal;
in float vMissing;    // > 0 in a triangle with a no-data vertex (a tiled field's stream normals)

uniform vec3 uCameraPosition;
uniform highp int uEarthKind; // earth.glsl: 0 the plane
uniform float uVerticalScale;
uniform vec3 uSkyLight;       // the sky's irradiance of level ground (web/render/shading/atmosphere.js)
uniform vec3 uTint;           // colour-by-level view: the level's colour
uniform float uTintAmount;    // 0 = ground colours, 1 = level colour only
uniform vec4 uLineColor;      // alpha > 0: draw flat lines (the hexagon outlines) in this colour
uniform int uMode;            // SHADING_MODES in web/render/renderer.js
uniform int uNormalSource;    // 0: the field's gradients, 1: the mesh's normals
uniform float uShadows;       // 1: the sun casts shadows
uniform float uOcclusionOn;   // 1: ambient occlusion modulates the sky light
uniform float uImageOpacity;  // the draped image over the ground colour, 0..1
uniform float uImageUnlit;    // 1: the image as it is (orthophotos carry their own shadows)
uniform int uHoleSource;      // NODATA_HOLES: 0 the field's presence texels, 1 the vertices' flags

#include "scattering.glsl"
#include "field_textures.glsl"
#include "ground_color.glsl"
#include "tonemap.glsl"
#include "image_drape.glsl"
#include "contours.glsl"

const int MODE_NATURAL = 0;
const int MODE_HYPSOMETRIC = 1;
const int MODE_SLOPE = 2;
const int MODE_HILLSHADE = 3;
const int MODE_PLAIN = 4;

out vec4 outColor;

// The former look: a height/slope ramp, a Lambert sun and a hemisphere sky, no textures.
vec3 plainShading(vec3 n) {
    float t = clamp((vHeight - uHeightRange.x) / max(uHeightRange.y - uHeightRange.x, 1e-3), 0.0, 1.0);
    float slope = 2.5 * (1.0 - n.y);
    vec3 color = mix(vec3(0.23, 0.36, 0.17), vec3(0.45, 0.38, 0.27), smoothstep(0.03, 0.3, t));
    color = mix(color, vec3(0.42, 0.40, 0.38), smoothstep(0.3, 0.65, slope));
    color = mix(color, vec3(0.93, 0.94, 0.97), smoothstep(0.64, 0.76, t) * (1.0 - smoothstep(0.55, 0.85, slope)));
    color = mix(color, uTint, uTintAmount);
    float sun = max(dot(n, normalize(vSunLocal)), 0.0);
    vec3 lit = color * (vec3(1.0, 0.96, 0.88) * sun * 1.1 + vec3(0.62, 0.74, 0.88) * (0.5 + 0.5 * n.y) * 0.35);
    return pow(lit, vec3(1.0 / 2.2));
}

// The terrain's colour at this pixel, before the contour lines.
vec4 groundShade() {
    if (uLineColor.a > 0.0) {
        return uLineColor;
    }
    if (uMode == MODE_PLAIN) {
        return vec4(plainShading(normalize(vNormal)), 1.0);
    }
    vec2 xz = vWorld.xz;
    // The draped image (straight alpha, display colours) and how much of it covers this pixel.
    vec4 image = drapedImage(xz);
    float imageShare = image.a * uImageOpacity;
    // The field's normal and height at this pixel; the mesh's (paper §7) when asked for.
    vec3 field = fieldSample(xz).xyz;
    bool fromField = uNormalSource == 0;
    vec3 n = fromField ? fieldNormal(field, uVerticalScale) : normalize(vNormal);
    float height = fromField ? field.z : vHeight;
    float sunLit = uShadows > 0.5 ? sunVisibility(xz) : 1.0;
    float ao = uOcclusionOn > 0.5 ? ambientOcclusion(xz) : 1.0;
    vec3 sunDirection = normalize(vSunLocal); // the local frame's: on the plane, uSunDirection
    float diffuse = max(dot(n, sunDirection), 0.0) * sunLit;
    float skyShare = ao * (0.5 + 0.5 * n.y);

    if (uMode == MODE_HILLSHADE) {
        // Grey proportional to the light, as GIS hillshades are (no tone curve).
        float shade = 0.8 * diffuse + 0.2 * skyShare;
        return vec4(mix(vec3(shade), image.rgb * (uImageUnlit > 0.5 ? 1.0 : shade), imageShare), 1.0);
    }
    if (uMode == MODE_HYPSOMETRIC || uMode == MODE_SLOPE) {
        vec3 trueNormal = normalize(vec3(n.x, n.y * uVerticalScale, n.z));
        vec3 ramp = uMode == MODE_HYPSOMETRIC ? hypsometric(height) : slopeRamp(degrees(acos(clamp(trueNormal.y, 0.0, 1.0))));
        ramp = mix(ramp, uTint, uTintAmount);
        // The ramps are display colours: shaded by the light, no tone curve.
        float light = min(1.0, 0.5 + 0.5 * (0.75 * diffuse + 0.25 * skyShare) / 0.6);
        return vec4(mix(ramp * light, image.rgb * (uImageUnlit > 0.5 ? 1.0 : light), imageShare), 1.0);
    }

    float noise = groundNoise(xz);
    vec3 ground = naturalGround(height, 1.0 - n.y, noise);
    // A lit image is an albedo in the same terms as the procedural ground's colours (ground_color.glsl).
    vec3 albedo = mix(mix(ground, image.rgb, uImageUnlit > 0.5 ? 0.0 : imageShare), uTint, uTintAmount);
    vec3 radiance;
    if (height < 0.0) {
        // Water: level, lit by the sky, with the sun's glint.
        vec3 view = uEarthKind == 0 ? normalize(uCameraPosition - vWorld) : normalize(vToEyeLocal);
        vec3 h = normalize(view + sunDirection);
        float glint = pow(max(h.y, 0.0), 400.0) * 6.0 * sunLit;
        radiance = albedo * (vSunlight * max(sunDirection.y, 0.0) * sunLit + uSkyLight) + vSunlight * glint;
    } else {
        radiance = albedo * (vSunlight * diffuse + uSkyLight * skyShare);
    }
    vec3 shaded = toneMap(radiance * vExtinction + vInscatter);
    // Unlit: the image's own colours over the shaded ground.
    return vec4(uImageUnlit > 0.5 ? mix(shaded, mix(image.rgb, uTint, uTintAmount), imageShare) : shaded, 1.0);
}

void main() {
#ifdef NODATA_HOLES
    // No-data as holes (the program variant the nodata=holes setting picks, so that every other
    // draw keeps early depth testing): where a field held whole has its presence, bilinear between
    // samples, under a half (each sample's own cell), or, for a tiled field, in every triangle
    // with a no-data corner (the fill there is the lowest height: no slope of it shows).
    if (uHoleSource == 0 ? fieldSample(vWorld.xz).w < 0.5 : vMissing > 0.0) discard;
#endif
    vec4 color = groundShade();
    // The hexagon outlines are lines of their own colour; everything else gets the contours.
    outColor = uLineColor.a > 0.0 ? color : vec4(withContours(color.rgb, vWorld.xz, vHeight), color.a);
}
