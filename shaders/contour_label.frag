#version 300 es
// A contour label's glyph: the atlas's premultiplied colour.
precision mediump float;

in vec2 vUv;
uniform sampler2D uAtlas;
out vec4 outColor;

void main() {
    outColor = texture(uAtlas, vUv);
}
