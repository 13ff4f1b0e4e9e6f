#version 300 es
// The sky: one triangle over the whole screen at the far plane (depth 1), drawn after the
// terrain so only uncovered pixels run the sky's fragment stage.
precision highp float;

layout(location = 0) in vec2 aCorner; // ATTRIB_SKY_CORNER in web/render/renderer.js: clip-space x, y

uniform mat4 uInverseViewProjection;

out vec3 vFar; // the point on the far plane behind this pixel, drawn metres

void main() {
    vec4 far = uInverseViewProjection * vec4(aCorner, 1.0, 1.0);
    vFar = far.xyz / far.w;
    gl_Position = vec4(aCorner, 1.0, 1.0);
}
