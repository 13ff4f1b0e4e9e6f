#version 300 es
// Terrain vertex shader: positions in metres (x east, y up, z south), normals from the core.
precision highp float;

layout(location = 0) in vec3 aPosition; // ATTRIB_POSITION in web/renderer.js
layout(location = 1) in vec3 aNormal;   // ATTRIB_NORMAL in web/renderer.js

uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;

out vec3 vNormal;
out float vHeight;   // metres, for the ground colour
out float vDistance; // metres from the camera, for aerial perspective
out vec2 vGround;    // x, z in metres, to hide what lies outside the field

void main() {
    vNormal = aNormal;
    vHeight = aPosition.y;
    vDistance = length(aPosition - uCameraPosition);
    vGround = aPosition.xz;
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
