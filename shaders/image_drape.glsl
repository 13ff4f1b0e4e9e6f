// The image layers draped on the terrain (web/render/shading/drape_layers.js), read by ground
// position and laid over each other bottom first. Each layer maps the ground to its own
// coordinates through a control grid (web/geo/warp_grid.js: exact at the nodes, bilinear
// between, within a quarter of a texel of the exact map), which is how an image in another CRS
// than the terrain's, or web map tiles in Web Mercator, land where they belong.
//   - An image file: pixel coordinates. Within MAX_TEXTURE_SIZE it is one layer of its
//     texture array; a larger one is tiles whose aprons repeat their neighbours' edge pixels
//     (no seam inside a tile), and the array's last layer is an overview of the whole image for
//     views where a screen pixel spans more image pixels than the apron holds.
//   - Web map tiles: tile coordinates at the table's zoom Z, relative to its first tile. The
//     table (web/render/shading/web_tile_textures.js) names, for each tile of zoom Z, the array
//     layer and zoom of the finest tile loaded that covers it: a coarser one while it loads.

const int DRAPE_OFF = 0;
const int DRAPE_IMAGE = 1;
const int DRAPE_TILES = 2;
const float NO_WARP = -1e29;   // below it a node has no value (warp_grid.js NO_VALUE)

uniform highp sampler2DArray uDrapeWarps;   // RG32F: the control grid of layer i is layer i
uniform highp sampler2DArray uDrapePages0;
uniform highp sampler2DArray uDrapePages1;
uniform highp sampler2DArray uDrapePages2;
uniform highp sampler2DArray uDrapePages3;
uniform highp usampler2D uDrapeTable0;
uniform highp usampler2D uDrapeTable1;
uniform highp usampler2D uDrapeTable2;
uniform highp usampler2D uDrapeTable3;
uniform int uDrapeKind[4];        // DRAPE_OFF, DRAPE_IMAGE or DRAPE_TILES
uniform float uDrapeOpacity[4];
uniform vec4 uDrapeWarp[4];       // grid node = xz * .xy; .zw: nodes across and down
uniform vec2 uDrapeSize[4];       // image: pixels
uniform vec4 uDrapeTiling[4];     // image: pixels between tile starts (x, y), tiles across and down
uniform vec3 uDrapeTile[4];       // image: texels a tile (x, y), apron pixels
uniform ivec3 uDrapeTable[4];     // tiles: the table's first tile (x, y) and its zoom Z

// Image pixels a screen pixel may span and still read the tiles: at most half the apron, so
// the mip level chosen (about log2 of the span) never reaches past a tile's apron.
const float IMAGE_TILE_MAX_SPAN = 4.0;

// The layer's coordinates at ground position xz, interpolated over its control grid; .z = 0
// where a node of the cell has no value.
vec3 drapeWarp(int slot, vec2 xz) {
    vec4 w = uDrapeWarp[slot];
    vec2 g = clamp(xz * w.xy, vec2(0.0), w.zw - 1.0);
    vec2 cell = min(floor(g), w.zw - 2.0);
    vec2 f = g - cell;
    ivec3 n = ivec3(cell, slot);
    vec2 a = texelFetch(uDrapeWarps, n, 0).xy;
    vec2 b = texelFetch(uDrapeWarps, n + ivec3(1, 0, 0), 0).xy;
    vec2 c = texelFetch(uDrapeWarps, n + ivec3(0, 1, 0), 0).xy;
    vec2 d = texelFetch(uDrapeWarps, n + ivec3(1, 1, 0), 0).xy;
    float valid = min(min(a.x, b.x), min(c.x, d.x)) > NO_WARP ? 1.0 : 0.0;
    return vec3(mix(mix(a, b, f.x), mix(c, d, f.x), f.y), valid);
}

vec4 drapeImage(highp sampler2DArray pages, int slot, vec2 p, vec2 dpx, vec2 dpy) {
    vec2 size = uDrapeSize[slot];
    vec2 uv = p / size;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return vec4(0.0);
    vec4 tiling = uDrapeTiling[slot];
    float tiles = tiling.z * tiling.w;
    if (tiles == 1.0) return textureGrad(pages, vec3(uv, 0.0), dpx / size, dpy / size);
    if (max(length(dpx), length(dpy)) > IMAGE_TILE_MAX_SPAN) return textureGrad(pages, vec3(uv, tiles), dpx / size, dpy / size);
    vec3 tileSize = uDrapeTile[slot];
    vec2 tile = clamp(floor(p / tiling.xy), vec2(0.0), tiling.zw - 1.0);
    vec2 local = (p - tile * tiling.xy + tileSize.z) / tileSize.xy;
    return textureGrad(pages, vec3(local, tile.y * tiling.z + tile.x), dpx / tileSize.xy, dpy / tileSize.xy);
}

vec4 drapeTiles(highp sampler2DArray pages, highp usampler2D table, int slot, vec2 t, vec2 dtx, vec2 dty) {
    ivec2 entryAt = ivec2(floor(t));
    if (any(lessThan(entryAt, ivec2(0))) || any(greaterThanEqual(entryAt, textureSize(table, 0)))) return vec4(0.0);
    uvec2 entry = texelFetch(table, entryAt, 0).rg;
    if (entry.x == 0u) return vec4(0.0);
    // The tile of zoom z = entry.y over this entry spans 2^k entries a side, k = Z - z; its
    // corner, in entries from the table's first tile, keeps the numbers small (float
    // precision at zoom 20).
    int k = uDrapeTable[slot].z - int(entry.y);
    ivec2 origin = uDrapeTable[slot].xy;
    ivec2 tile = (entryAt + origin) >> k;
    float scale = 1.0 / exp2(float(k));
    vec2 uv = (t - vec2((tile << k) - origin)) * scale;
    return textureGrad(pages, vec3(uv, float(entry.x - 1u)), dtx * scale, dty * scale);
}

vec4 drapeLayer(int slot, highp sampler2DArray pages, highp usampler2D table, vec2 xz) {
    if (uDrapeKind[slot] == DRAPE_OFF) return vec4(0.0);
    vec3 p = drapeWarp(slot, xz);
    // Derivatives in uniform control flow (the kind is a uniform), before the branches below.
    vec2 dpx = dFdx(p.xy), dpy = dFdy(p.xy);
    if (p.z == 0.0) return vec4(0.0);
    vec4 color = uDrapeKind[slot] == DRAPE_IMAGE ? drapeImage(pages, slot, p.xy, dpx, dpy) : drapeTiles(pages, table, slot, p.xy, dpx, dpy);
    return vec4(color.rgb, color.a * uDrapeOpacity[slot]);
}

// `top` over `under`, both with straight alpha.
vec4 over(vec4 under, vec4 top) {
    float a = top.a + under.a * (1.0 - top.a);
    return a > 0.0 ? vec4((top.rgb * top.a + under.rgb * under.a * (1.0 - top.a)) / a, a) : vec4(0.0);
}

// The image layers' colour (straight alpha, display colours) at ground position xz; alpha 0 where none covers it.
vec4 drapedImage(vec2 xz) {
    vec4 color = drapeLayer(0, uDrapePages0, uDrapeTable0, xz);
    color = over(color, drapeLayer(1, uDrapePages1, uDrapeTable1, xz));
    color = over(color, drapeLayer(2, uDrapePages2, uDrapeTable2, xz));
    return over(color, drapeLayer(3, uDrapePages3, uDrapeTable3, xz));
}
