// Ground colours (paper §7: "procedural ground colour from height, slope and per-pixel noise"),
// and the analysis ramps (hypsometric, slope).

uniform vec2 uHeightRange;  // lowest and highest true height of the field, metres
uniform float uSnowLine;    // true metres above which gentle ground is snow
uniform float uTreeLine;    // true metres above which vegetation gives way to bare soil
uniform float uNoiseScale;  // metres: the size of the smallest noise feature (about a sample)

float hash12(vec2 p) {
    vec3 q = fract(vec3(p.xyx) * 0.1031);
    q += dot(q, q.yzx + 33.33);
    return fract((q.x + q.y) * q.z);
}

// Value noise in [0, 1] with smooth interpolation.
float valueNoise(vec2 p) {
    vec2 i = floor(p), f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    float a = hash12(i), b = hash12(i + vec2(1.0, 0.0)), c = hash12(i + vec2(0.0, 1.0)), d = hash12(i + vec2(1.0, 1.0));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// Two octaves, the finer a quarter of a sample across (detail below the field's resolution);
// `xz` in metres. Large positions lose precision in float, so they are wrapped at a period far
// above any feature.
float groundNoise(vec2 xz) {
    vec2 p = mod(xz / uNoiseScale, 4096.0);
    return 0.6 * valueNoise(p * 0.3) + 0.4 * valueNoise(p * 4.0);
}

// Natural colours: water over the sea floor below sea level, vegetation and soil low, rock
// (banded like sediment) on steep slopes, snow on high gentle ground. `steep` is the drawn
// slope as 1 - n.y, height in true metres.
vec3 naturalGround(float height, float steep, float noise) {
    if (height < 0.0) {
        // The sea: shallow shelves turquoise, the deep ocean dark blue.
        float depth = smoothstep(0.0, 4000.0, -height + 300.0 * (noise - 0.5));
        return mix(vec3(0.05, 0.16, 0.2), vec3(0.01, 0.03, 0.09), depth);
    }
    float n = noise - 0.5;
    vec3 lowland = vec3(0.14, 0.19, 0.08);
    vec3 upland = vec3(0.25, 0.24, 0.14);
    vec3 soil = vec3(0.32, 0.27, 0.2);
    float tree = clamp((height - 0.35 * uTreeLine) / (0.65 * uTreeLine) + 0.4 * n, 0.0, 1.0);
    vec3 color = mix(lowland, upland, smoothstep(0.0, 0.6, tree));
    // Bare soil: above the tree line, and in patches (noise) and on moderate slopes below it.
    color = mix(color, soil, smoothstep(0.25, 0.75, tree + 1.2 * n + 1.5 * steep));
    // Sedimentary bands: the rock's hue follows the height, broken up by the noise.
    float band = 0.5 + 0.5 * sin(height / 55.0 + 6.0 * n);
    vec3 rock = mix(vec3(0.3, 0.27, 0.25), vec3(0.48, 0.22, 0.12), band * 0.85);
    color = mix(color, rock, smoothstep(0.1, 0.25, steep + 0.15 * n));
    float snow = smoothstep(-250.0, 250.0, height - uSnowLine + 400.0 * n) * (1.0 - smoothstep(0.3, 0.5, steep + 0.2 * n));
    return mix(color, vec3(0.95, 0.96, 0.98), snow);
}

// A classic hypsometric tint: sea blues, then green lowland to brown, grey and white peaks,
// over the field's own height range.
vec3 hypsometric(float height) {
    if (height < 0.0) return mix(vec3(0.55, 0.75, 0.9), vec3(0.1, 0.2, 0.5), smoothstep(0.0, max(-uHeightRange.x, 1.0), -height));
    float t = clamp((height - max(uHeightRange.x, 0.0)) / max(uHeightRange.y - max(uHeightRange.x, 0.0), 1e-3), 0.0, 1.0);
    vec3 c = mix(vec3(0.2, 0.5, 0.25), vec3(0.55, 0.7, 0.35), smoothstep(0.0, 0.25, t));
    c = mix(c, vec3(0.85, 0.78, 0.5), smoothstep(0.2, 0.45, t));
    c = mix(c, vec3(0.6, 0.42, 0.28), smoothstep(0.4, 0.7, t));
    c = mix(c, vec3(0.6, 0.58, 0.56), smoothstep(0.7, 0.85, t));
    return mix(c, vec3(0.97), smoothstep(0.85, 1.0, t));
}

// Slope classes of the true (unexaggerated) slope: green flat, yellow 15°, orange 30°, red 45°,
// purple from 60°.
vec3 slopeRamp(float degreesSlope) {
    vec3 c = mix(vec3(0.3, 0.65, 0.3), vec3(0.95, 0.9, 0.3), smoothstep(0.0, 15.0, degreesSlope));
    c = mix(c, vec3(0.95, 0.55, 0.15), smoothstep(15.0, 30.0, degreesSlope));
    c = mix(c, vec3(0.85, 0.15, 0.1), smoothstep(30.0, 45.0, degreesSlope));
    return mix(c, vec3(0.45, 0.1, 0.5), smoothstep(45.0, 60.0, degreesSlope));
}
