// Tone mapping of the final image (paper §7: "a simple tone mapping"): an exposure curve
// 1 - exp(-k L) that never clips, then sRGB-like gamma.
uniform float uExposure;

vec3 toneMap(vec3 radiance) {
    vec3 mapped = 1.0 - exp(-uExposure * radiance);
    return pow(mapped, vec3(1.0 / 2.2));
}
