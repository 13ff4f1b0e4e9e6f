#version 300 es
// One glyph of a contour label (web/render/contours/labels.js): a screen-aligned quad, turned
// along the contour, placed in pixels by the page (which did the projection and the occlusion test).
precision highp float;

layout(location = 0) in vec2 aCenter; // the glyph's centre, pixels from the bottom left
layout(location = 1) in vec2 aAxis;   // the text's direction on the screen (unit)
layout(location = 2) in float aGlyph; // index in the atlas (glyph_atlas.js GLYPHS)

uniform vec2 uViewport;   // pixels
uniform vec2 uGlyphSize;  // the quad's pixels (cell width, height)
uniform float uGlyphs;    // glyphs in the atlas

out vec2 vUv;

void main() {
    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1); // a triangle strip: (0,0) (1,0) (0,1) (1,1)
    vec2 local = (corner - 0.5) * uGlyphSize;
    vec2 up = vec2(-aAxis.y, aAxis.x);
    vec2 pixel = aCenter + aAxis * local.x + up * local.y;
    vUv = vec2((aGlyph + corner.x) / uGlyphs, 1.0 - corner.y);
    gl_Position = vec4(pixel / uViewport * 2.0 - 1.0, 0.0, 1.0);
}
