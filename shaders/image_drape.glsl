// The draped image (web/render/shading/image_textures.js), read by ground position. An image
// within MAX_TEXTURE_SIZE is one layer; a larger one is tiles whose aprons repeat their
// neighbours' edge pixels, so a lookup inside one tile never sees a seam, plus an overview of
// the whole image for views where a screen pixel spans more image pixels than the apron holds.

uniform highp sampler2DArray uImageTiles;
uniform sampler2D uImageOverview;
uniform float uImageOn;        // 1: an image is draped
uniform vec4 uImageMap;        // texture uv = xz * .xy + .zw (xz: ground metres)
uniform vec2 uImageSize;       // image pixels
uniform vec4 uImageTiling;     // pixels between tile starts (x, y), tiles across and down
uniform vec3 uImageTile;       // texels a tile (x, y), apron pixels

// Image pixels a screen pixel may span and still read the tiles: at most half the apron, so
// the mip level chosen (about log2 of the span) never reaches past a tile's apron.
const float IMAGE_TILE_MAX_SPAN = 4.0;

// The image's colour (straight alpha) at ground position xz; alpha 0 outside the image.
vec4 drapedImage(vec2 xz) {
    vec2 uv = xz * uImageMap.xy + uImageMap.zw;
    vec2 p = uv * uImageSize;
    // Derivatives in uniform control flow, before any branch.
    vec2 dpx = dFdx(p), dpy = dFdy(p);
    if (uImageOn < 0.5 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return vec4(0.0);
    if (uImageTiling.z * uImageTiling.w == 1.0) {
        return textureGrad(uImageTiles, vec3(uv, 0.0), dpx / uImageSize, dpy / uImageSize);
    }
    float span = max(length(dpx), length(dpy));
    if (span > IMAGE_TILE_MAX_SPAN) return textureGrad(uImageOverview, uv, dpx / uImageSize, dpy / uImageSize);
    vec2 tile = clamp(floor(p / uImageTiling.xy), vec2(0.0), uImageTiling.zw - 1.0);
    vec2 local = (p - tile * uImageTiling.xy + uImageTile.z) / uImageTile.xy;
    return textureGrad(uImageTiles, vec3(local, tile.y * uImageTiling.z + tile.x), dpx / uImageTile.xy, dpy / uImageTile.xy);
}
