#version 300 es
// Terrain vertex stage: the geomorph blend of paper §7 (src/geomorph.h has the same formula for
// the core), the overhang clamped to the field, and the atmospheric scattering of §7 per vertex.
precision highp float;

layout(location = 0) in vec3 aPosition;  // ATTRIB_POSITION in web/render/renderer.js: true position, unscaled height
layout(location = 1) in vec4 aNormal;    // ATTRIB_NORMAL: snorm16, averaged from the adjacent triangles; w 1 at no-data
layout(location = 2) in float aMorphFromHeight; // ATTRIB_MORPH_FROM: height of the coarser surface under the vertex, where the blend starts
layout(location = 3) in float aMorphKey; // ATTRIB_MORPH_KEY: 0 at rest, f+1 blending in, -(f+1) out, since frame f
layout(location = 4) in ivec2 aLattice;  // ATTRIB_LATTICE: the vertex's lattice point, exact (half columns east, rows south)

// Drawn relative to the eye (web/render/shading/eye_anchor.js): a float holds a world field's
// metres only to about 4 m, so the vertex's place is found from its exact lattice point as an
// offset from an anchor near the eye, drawn in the anchor's tangent frame, then turned into the
// drawn frame and taken from the eye in doubles by the page. Near the eye every number is small.
uniform ivec2 uAnchorLattice;  // the anchor's lattice point (half columns, rows)
uniform vec2 uAnchorRest;      // flat metres from that lattice point to the anchor
uniform vec2 uLatticeMetres;   // flat metres of a half column and a row
uniform ivec2 uLatticeLast;    // the field's last half column and row: the overhang is clamped there
uniform float uAnchorLatitude; // the anchor's latitude (radians, geographic)
uniform mat3 uAnchorAxes;      // the anchor's east, up and south in the drawn frame
uniform vec3 uAnchorFromEye;   // drawn metres from the eye to the anchor's ground point
uniform mat4 uViewProjectionFromEye; // the view-projection of an eye at the drawn frame's origin
uniform vec3 uCameraPosition;  // drawn metres (on the curved Earth, in its frame: earth.glsl)
uniform float uEyeHeight;      // the eye's height above the surface's zero, true metres
uniform float uFrame;          // the core's blend clock (hexlod_lod_frame)
uniform float uMorphFrames;    // frames a blend takes; 0: no geomorphing
uniform float uVerticalScale;  // height exaggeration
uniform vec2 uExtent;          // the field's rectangle, metres (x, z)

#include "scattering.glsl"
#include "earth.glsl"

out float vMissing;  // 1 at a no-data vertex (terrain.frag's holes)
out vec3 vNormal;     // the mesh's normal (paper §7), in the local frame (x east, y up, z south)
out vec3 vWorld;      // flat metres: x, exaggerated height, z (where the field's textures are read)
out vec3 vSunLocal;   // towards the sun in the local frame (the drawn frame's on the plane)
out vec3 vToEyeLocal; // towards the eye in the local frame, unit
out float vHeight;    // true height, metres, for the ground colour
out vec3 vExtinction; // Fex from the vertex to the eye
out vec3 vInscatter;  // Lin along that ray
out vec3 vSunlight;   // the sun's light at the vertex (dimmed by the air above it)

void main() {
    float w = 1.0;
    if (aMorphKey != 0.0 && uMorphFrames > 0.0) {
        float t = clamp((uFrame - (abs(aMorphKey) - 1.0)) / uMorphFrames, 0.0, 1.0);
        w = aMorphKey > 0.0 ? t : 1.0 - t;
    }
    vec3 p = vec3(aPosition.x, aMorphFromHeight + (aPosition.y - aMorphFromHeight) * w, aPosition.z); // blends are vertical
    // The lattice reaches past the field on the east, west and south (docs/DESIGN.md). Moving
    // those vertices onto the field's edge, where the core's clamped lookups already put
    // their heights, folds the overhang onto the border: cells wholly outside become
    // zero-area and draw nothing, cells across the edge end at it. No fragment is discarded.
    p.xz = clamp(p.xz, vec2(0.0), uExtent);
    ivec2 lattice = clamp(aLattice, ivec2(0), uLatticeLast);
    vHeight = p.y;
    p.y *= uVerticalScale;
    // Scaling heights by s scales normals by the inverse transpose: (nx, ny / s, nz).
    vNormal = vec3(aNormal.x, aNormal.y / uVerticalScale, aNormal.z);
    vMissing = aNormal.w;
    vWorld = p;

    // On the curved Earth the vertex is drawn on it (earth.glsl); the lighting works in the
    // local frame, where "up" is the surface's.
    vec2 fromAnchor = vec2(lattice - uAnchorLattice) * uLatticeMetres - uAnchorRest; // exact: small integers
    vec3 ray = uAnchorAxes * earthOffset(fromAnchor, p.y, uAnchorLatitude) + uAnchorFromEye;
    vec3 east, up, south;
    earthFrame(p.xz, east, up, south);
    vSunLocal = vec3(dot(uSunDirection, east), dot(uSunDirection, up), dot(uSunDirection, south));
    vec3 toEye = normalize(-ray);
    vToEyeLocal = vec3(dot(toEye, east), dot(toEye, up), dot(toEye, south));
    // The air is not exaggerated: optical depths follow the ray in true metres.
    vec3 rayLocal = vec3(dot(ray, east), dot(ray, up), dot(ray, south));
    float s = length(vec3(rayLocal.x, rayLocal.y / uVerticalScale, rayLocal.z));
    float eye = uEyeHeight;
    float depthR = airPath(eye, vHeight, s, uScaleHeight.x);
    float depthM = airPath(eye, vHeight, s, uScaleHeight.y);
    vSunlight = sunlightAt(vHeight);
    // The air along the ray is lit by sunlight of its mean height.
    scatter(depthR, depthM, dot(normalize(ray), uSunDirection), sunlightAt(0.5 * (eye + vHeight)),
        vExtinction, vInscatter);
    gl_Position = uViewProjectionFromEye * vec4(ray, 1.0);
}
