#version 300 es
// Terrain fragment shader: procedural ground colour from height and slope, lit by one sun
// and a sky ambient term, faded into the sky colour with distance.
precision highp float;

in vec3 vNormal;
in float vHeight;
in float vDistance;

uniform vec3 uSunDirection;   // unit vector towards the sun
uniform vec2 uHeightRange;    // lowest and highest drawn height, metres
uniform vec3 uSkyColor;
uniform float uFogDistance;   // metres at which the terrain is about 63% sky

out vec4 outColor;

vec3 groundColor(float t, float slope) {
    vec3 low = vec3(0.23, 0.36, 0.17);    // vegetation
    vec3 mid = vec3(0.45, 0.38, 0.27);    // dry ground
    vec3 rock = vec3(0.42, 0.40, 0.38);
    vec3 snow = vec3(0.93, 0.94, 0.97);
    vec3 color = mix(low, mid, smoothstep(0.03, 0.3, t));
    color = mix(color, rock, smoothstep(0.3, 0.65, slope));
    return mix(color, snow, smoothstep(0.64, 0.76, t) * (1.0 - smoothstep(0.55, 0.85, slope)));
}

void main() {
    vec3 n = normalize(vNormal);
    float t = clamp((vHeight - uHeightRange.x) / max(uHeightRange.y - uHeightRange.x, 1e-3), 0.0, 1.0);
    float slope = 1.0 - n.y;
    vec3 albedo = groundColor(t, slope * 2.5);
    float sun = max(dot(n, uSunDirection), 0.0);
    float sky = 0.5 + 0.5 * n.y;
    vec3 lit = albedo * (vec3(1.0, 0.96, 0.88) * sun * 1.1 + uSkyColor * sky * 0.35);
    float fog = 1.0 - exp(-vDistance / uFogDistance);
    vec3 color = mix(lit, uSkyColor, fog);
    outColor = vec4(pow(color, vec3(1.0 / 2.2)), 1.0);
}
