// Contour lines (web/render/contours/): where the full-resolution field crosses a multiple of
// the interval, per pixel. The height at the pixel's ground position is the field's bilinear
// height of its raw samples (texelFetch of the exact height texture, interpolated here); the
// distance to the nearest level in metres over the height's change per pixel (fwidth) is the
// distance in pixels, so lines keep their width near and far and are antialiased.

uniform highp usampler2DArray uContourHeights;
uniform vec2 uContourTexel;   // metres between texels, x and z
uniform vec2 uContourTexels;  // texels across the field, x and z
uniform vec2 uContourStep;    // texels between the origins of neighbouring tiles (tile size - 1)
uniform vec2 uContourTiles;   // tiles across x and z
uniform int uContourKind;     // how a texel's bits read: 0 unsigned, 1 int16, 2 float32
uniform vec2 uContourScale;   // metres = raw * x + y
uniform vec4 uContour;        // interval (m), major step (m), line width (px) of a minor line, 0: off
uniform int uContourSource;   // 0: the exact height texture, 1: the mesh's height (a streamed field)

float contourRaw(uvec4 texel) {
    uint v = texel.r;
    if (uContourKind == 1) return float(int(v << 16) >> 16); // sign-extend the int16 bits
    if (uContourKind == 2) return uintBitsToFloat(v);
    return float(v);
}

// The field's bilinear height (true metres) at ground position xz.
float contourHeight(vec2 xz) {
    vec2 t = clamp(xz / uContourTexel, vec2(0.0), uContourTexels - 1.0);
    vec2 cell = min(floor(t), uContourTexels - 2.0);
    cell = max(cell, vec2(0.0));
    vec2 f = t - cell;
    vec2 tile = min(floor(cell / uContourStep), uContourTiles - 1.0);
    ivec2 p = ivec2(cell - tile * uContourStep);
    int layer = int(tile.y * uContourTiles.x + tile.x);
    ivec2 last = ivec2(uContourStep); // a one-texel-wide field: the neighbour is the texel itself
    ivec2 q = min(p + 1, last);
    float h00 = contourRaw(texelFetch(uContourHeights, ivec3(p.x, p.y, layer), 0));
    float h10 = contourRaw(texelFetch(uContourHeights, ivec3(q.x, p.y, layer), 0));
    float h01 = contourRaw(texelFetch(uContourHeights, ivec3(p.x, q.y, layer), 0));
    float h11 = contourRaw(texelFetch(uContourHeights, ivec3(q.x, q.y, layer), 0));
    float raw = mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
    return raw * uContourScale.x + uContourScale.y;
}

// Coverage (0..1) of a line of `widthPx` at the levels `step` metres apart, from the height
// `h` and its change per pixel; fades out where the lines crowd closer than a few pixels.
float contourCoverage(float h, float perPixel, float step, float widthPx) {
    // The level a hair above its value: samples lying on it (integer heights and a whole
    // interval) count as below, so a plateau at a level is not a patch of ink but is bounded by its line.
    float metres = abs(fract(h / step + 0.5 - 1e-4) - 0.5) * step;
    float px = metres / max(perPixel, 1e-9);
    float crowd = smoothstep(3.0, 8.0, step / max(perPixel, 1e-9));
    return clamp(0.5 * widthPx + 0.5 - px, 0.0, 1.0) * crowd;
}

// The ground colour with the contour lines over it.
vec3 withContours(vec3 color, vec2 xz, float meshHeight) {
    if (uContour.w == 0.0) return color;
    float h = uContourSource == 0 ? contourHeight(xz) : meshHeight;
    float perPixel = fwidth(h);
    float minor = contourCoverage(h, perPixel, uContour.x, uContour.z);
    float major = contourCoverage(h, perPixel, uContour.y, 2.0 * uContour.z);
    vec3 ink = vec3(0.22, 0.12, 0.04);
    color = mix(color, ink, 0.75 * minor);
    return mix(color, ink * 0.6, 0.95 * major);
}
