// The exact heights the contour lines are drawn from: the field's raw samples at their native
// depth in an unsigned-integer texture array (R8UI for u8, R16UI for u16 and the bits of i16,
// R32UI for the bits of f32), read with texelFetch and interpolated bilinearly in the shader
// (shaders/contours.glsl), so a pixel's height is the field's own bilinear height to the last
// bit of its samples. The gradient texture's half floats step by 4 m at 8000 m: too coarse.
// Tiles of at most MAX_TEXTURE_SIZE a side share their edge texels, so the four texels of a
// cell are always in one tile. Made only while contours are on; larger than MAX_TEXELS, it keeps
// every stride-th sample (and says so).

export const TEXTURE_UNIT_CONTOUR_HEIGHTS = 5; // after the field's (0-2) and the image layers' control grids (3)
/**
 * Texels at most: 8193², 2^26 and one more row and column, so that the paper's 16385² field
 * keeps every 2nd sample (128 MB at 16 bits, 256 MB for a float field); past that a stride.
 */
export const MAX_TEXELS = 8193 * 8193;
/** How the shader reads a texel's bits (uContourKind): as unsigned, as int16, as float32. */
const KINDS = { u8: 0, u16: 0, i16: 1, f32: 2 };

/** Sizes of the texture for a field: the stride, texels per axis, tiles. Pure: tests and the page's note use it. */
export function heightTexturePlan(width, height, maxTile, maxTexels = MAX_TEXELS) {
  // Texels per axis: every stride-th sample, and the last sample, so the texture spans the field.
  const texels = (n, k) => Math.ceil((n - 1) / k) + 1;
  let stride = Math.max(1, Math.floor(Math.sqrt((width * height) / maxTexels)));
  while (texels(width, stride) * texels(height, stride) > maxTexels) stride += 1;
  const texelsX = texels(width, stride), texelsZ = texels(height, stride);
  const tileX = Math.min(texelsX, maxTile), tileZ = Math.min(texelsZ, maxTile);
  const tilesX = Math.max(1, Math.ceil((texelsX - 1) / (tileX - 1))), tilesZ = Math.max(1, Math.ceil((texelsZ - 1) / (tileZ - 1)));
  return { stride, texelsX, texelsZ, tileX, tileZ, tilesX, tilesZ };
}

export class ContourHeights {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.texture = null;
    this.plan = null;
    this.key = null; // the terrain and field it was made from
  }

  /** The context was lost: made again when next needed. */
  forgetGl() {
    this.texture = null;
    this.key = null;
  }

  release() {
    if (this.texture) this.gl.deleteTexture(this.texture);
    this.forgetGl();
  }

  /**
   * Makes the texture for this terrain if it is not made yet (allocates only then). False when
   * the terrain has no whole field (a streamed, tiled terrain).
   * @param {import('../../core/core.js').Terrain} terrain @param {{heightScale?: number, heightOffset?: number}} field
   */
  prepare(terrain, field) {
    if (!terrain || terrain.handle === 0 || terrain.tiled) return false;
    if (this.key === terrain && this.field === field) return true;
    this.release();
    const gl = this.gl, start = performance.now();
    const plan = this.plan = heightTexturePlan(terrain.width, terrain.height, gl.getParameter(gl.MAX_TEXTURE_SIZE));
    const type = terrain.sampleType;
    const samples = terrain.samples();
    // The same bytes as unsigned integers of the sample's size (i16 and f32 are reinterpreted in the shader).
    const Bits = samples.BYTES_PER_ELEMENT === 1 ? Uint8Array : samples.BYTES_PER_ELEMENT === 2 ? Uint16Array : Uint32Array;
    const bits = new Bits(samples.buffer, samples.byteOffset, samples.length);
    const [internal, format, glType] = samples.BYTES_PER_ELEMENT === 1 ? [gl.R8UI, gl.RED_INTEGER, gl.UNSIGNED_BYTE]
      : samples.BYTES_PER_ELEMENT === 2 ? [gl.R16UI, gl.RED_INTEGER, gl.UNSIGNED_SHORT] : [gl.R32UI, gl.RED_INTEGER, gl.UNSIGNED_INT];
    const texture = this.texture = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_CONTOUR_HEIGHTS);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, internal, plan.tileX, plan.tileZ, plan.tilesX * plan.tilesZ);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    const { stride, tileX, tileZ, tilesX, tilesZ } = plan, width = terrain.width, height = terrain.height;
    const scratch = stride > 1 ? new Bits(tileX * tileZ) : null;
    for (let tz = 0; tz < tilesZ; ++tz) {
      for (let tx = 0; tx < tilesX; ++tx) {
        const x0 = tx * (tileX - 1), z0 = tz * (tileZ - 1); // first texel of the tile
        const w = Math.min(tileX, plan.texelsX - x0), h = Math.min(tileZ, plan.texelsZ - z0);
        const layer = tz * tilesX + tx;
        if (stride === 1) {
          // Straight from WASM memory: the tile is a window of the field's rows.
          gl.pixelStorei(gl.UNPACK_ROW_LENGTH, width);
          gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, layer, w, h, 1, format, glType, bits, z0 * width + x0);
          gl.pixelStorei(gl.UNPACK_ROW_LENGTH, 0);
        } else {
          for (let j = 0; j < h; ++j) {
            const row = Math.min(height - 1, (z0 + j) * stride) * width;
            for (let i = 0; i < w; ++i) scratch[j * w + i] = bits[row + Math.min(width - 1, (x0 + i) * stride)];
          }
          gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, layer, w, h, 1, format, glType, scratch, 0);
        }
      }
    }
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    for (const [name, value] of [[gl.TEXTURE_MIN_FILTER, gl.NEAREST], [gl.TEXTURE_MAG_FILTER, gl.NEAREST],
      [gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE], [gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE]]) gl.texParameteri(gl.TEXTURE_2D_ARRAY, name, value);
    this.kind = KINDS[type];
    this.scale = field?.heightScale ?? 1;
    this.offset = field?.heightOffset ?? 0;
    // Metres between texels: the last texel is the last sample, wherever the stride ends.
    this.texelX = terrain.spacingX * stride;
    this.texelZ = terrain.spacingY * stride;
    this.key = terrain;
    this.field = field;
    this.bytes = plan.tileX * plan.tileZ * plan.tilesX * plan.tilesZ * samples.BYTES_PER_ELEMENT;
    this.ms = performance.now() - start;
    return true;
  }

  /** Binds the texture and sets the uniforms of shaders/contours.glsl. */
  setUniforms(u, terrain) {
    const gl = this.gl, p = this.plan;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_CONTOUR_HEIGHTS);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    gl.uniform1i(u.uContourHeights, TEXTURE_UNIT_CONTOUR_HEIGHTS);
    // The cell size may have changed since: texels are where the samples now are.
    const stride = p.stride;
    gl.uniform2f(u.uContourTexel, terrain.spacingX * stride, terrain.spacingY * stride);
    gl.uniform2f(u.uContourTexels, p.texelsX, p.texelsZ);
    gl.uniform2f(u.uContourStep, p.tileX - 1, p.tileZ - 1);
    gl.uniform2f(u.uContourTiles, p.tilesX, p.tilesZ);
    gl.uniform1i(u.uContourKind, this.kind);
    gl.uniform2f(u.uContourScale, this.scale, this.offset);
  }
}
