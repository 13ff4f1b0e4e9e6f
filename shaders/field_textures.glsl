// What the shading reads from the full-resolution field (web/render/shading/field_shading.js), by
// ground position, whatever the mesh's level of detail:
//   uGradients     dh/dx, dh/dz (true metres per metre), the height (true metres) and the
//                  presence (0 where the sample was no-data) of every sample, so normals and ground colours do not change with the mesh; a texture array whose
//                  layers are tiles of at most MAX_TEXTURE_SIZE per side; neighbouring tiles
//                  share their edge texels so bilinear filtering stays inside one tile.
//   uSunVisibility the sun's shadow (1 lit, 0 in shadow), 8 bits, one sweep per sun direction.
//   uOcclusion     the 8-bit ambient-occlusion term of paper §7 (sky light seen by the ground).

uniform highp sampler2DArray uGradients;
uniform vec2 uGradientTexel;  // metres per texel, x and z
uniform vec2 uGradientStep;   // texels between the origins of neighbouring tiles (tile size - 1)
uniform vec2 uGradientTile;   // texels per tile, x and z
uniform vec2 uGradientTiles;  // tiles across x and z
uniform sampler2D uSunVisibility;
uniform vec4 uSunVisibilityMap; // uv = xz * .xy + .zw
uniform sampler2D uOcclusion;
uniform vec4 uOcclusionMap;     // uv = xz * .xy + .zw

// The height gradient (xy), height (z) and presence (w) at ground position xz (metres). Mip levels are chosen
// from the continuous texel position, not the tile-local one, so tile seams do not jump to a
// coarse mip.
vec4 fieldSample(vec2 xz) {
    vec2 texel = xz / uGradientTexel;
    // One tile (any field up to MAX_TEXTURE_SIZE a side): no seams, implicit derivatives.
    if (uGradientTiles.x * uGradientTiles.y == 1.0) return texture(uGradients, vec3((texel + 0.5) / uGradientTile, 0.0));
    vec2 tile = clamp(floor(texel / uGradientStep), vec2(0.0), uGradientTiles - 1.0);
    vec2 uv = (texel - tile * uGradientStep + 0.5) / uGradientTile;
    vec2 dx = dFdx(texel) / uGradientTile, dy = dFdy(texel) / uGradientTile;
    return textureGrad(uGradients, vec3(uv, tile.y * uGradientTiles.x + tile.x), dx, dy);
}

// The drawn (exaggerated) unit normal from the field's gradient.
vec3 fieldNormal(vec3 field, float verticalScale) {
    vec2 g = field.xy * verticalScale;
    return normalize(vec3(-g.x, 1.0, -g.y));
}

float sunVisibility(vec2 xz) {
    return texture(uSunVisibility, xz * uSunVisibilityMap.xy + uSunVisibilityMap.zw).r;
}

float ambientOcclusion(vec2 xz) {
    return texture(uOcclusion, xz * uOcclusionMap.xy + uOcclusionMap.zw).r;
}
