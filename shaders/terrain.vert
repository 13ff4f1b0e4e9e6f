#version 300 es
// Terrain vertex shader: positions in metres (x east, y up, z south), normals from the core,
// and the geomorph blend of paper §7 (src/geomorph.h has the same formula for the core).
precision highp float;

layout(location = 0) in vec3 aPosition;  // ATTRIB_POSITION in web/renderer.js: true position, unscaled height
layout(location = 1) in vec3 aNormal;    // ATTRIB_NORMAL: snorm16, averaged from the adjacent triangles
layout(location = 2) in vec3 aMorphFrom; // ATTRIB_MORPH_FROM: the coarser surface where the blend starts
layout(location = 3) in float aMorphKey; // ATTRIB_MORPH_KEY: 0 at rest, f+1 blending in, -(f+1) out, since frame f

uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;
uniform float uFrame;          // the core's blend clock (hexlod_lod_frame)
uniform float uMorphFrames;    // frames a blend takes; 0: no geomorphing
uniform float uVerticalScale;  // height exaggeration

out vec3 vNormal;
out float vHeight;   // metres (exaggerated), for the ground colour
out float vDistance; // metres from the camera, for aerial perspective
out vec2 vGround;    // x, z in metres, to hide what lies outside the field

void main() {
    float w = 1.0;
    if (aMorphKey != 0.0 && uMorphFrames > 0.0) {
        float t = clamp((uFrame - (abs(aMorphKey) - 1.0)) / uMorphFrames, 0.0, 1.0);
        w = aMorphKey > 0.0 ? t : 1.0 - t;
    }
    vec3 p = aMorphFrom + (aPosition - aMorphFrom) * w;
    p.y *= uVerticalScale;
    // Scaling heights by s scales normals by the inverse transpose: (nx, ny / s, nz).
    vNormal = vec3(aNormal.x, aNormal.y / uVerticalScale, aNormal.z);
    vHeight = p.y;
    vDistance = length(p - uCameraPosition);
    vGround = p.xz;
    gl_Position = uViewProjection * vec4(p, 1.0);
}
