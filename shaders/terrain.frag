#version 300 es
// Terrain fragment shader: procedural ground colour from height and slope, lit by one sun
// and a sky ambient term, faded into the sky colour with distance.
precision highp float;

in vec3 vNormal;
in float vHeight;
in float vDistance;
in vec2 vGround;              // x, z in metres

uniform vec3 uSunDirection;   // unit vector towards the sun
uniform vec2 uHeightRange;    // lowest and highest drawn height, metres
uniform vec3 uSkyColor;
uniform float uFogDistance;   // metres at which the terrain is about 63% sky
uniform vec3 uTint;           // colour-by-level view: the level's colour
uniform float uTintAmount;    // 0 = ground colours, 1 = level colour only
uniform vec2 uExtent;         // the field's rectangle, metres (x, z); the mesh may reach past it
uniform vec4 uLineColor;      // alpha > 0: draw flat lines (the hexagon outlines) in this colour

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
    // The lattice extends past the field on the east, west and south: hide what lies outside.
    if (vGround.x < 0.0 || vGround.y < 0.0 || vGround.x > uExtent.x || vGround.y > uExtent.y) discard;
    if (uLineColor.a > 0.0) {
        outColor = uLineColor;
        return;
    }
    vec3 n = normalize(vNormal);
    float t = clamp((vHeight - uHeightRange.x) / max(uHeightRange.y - uHeightRange.x, 1e-3), 0.0, 1.0);
    float slope = 1.0 - n.y;
    vec3 albedo = mix(groundColor(t, slope * 2.5), uTint, uTintAmount);
    float sun = max(dot(n, uSunDirection), 0.0);
    float sky = 0.5 + 0.5 * n.y;
    vec3 lit = albedo * (vec3(1.0, 0.96, 0.88) * sun * 1.1 + uSkyColor * sky * 0.35);
    float fog = 1.0 - exp(-vDistance / uFogDistance);
    vec3 color = mix(lit, uSkyColor, fog);
    outColor = vec4(pow(color, vec3(1.0 / 2.2)), 1.0);
}
