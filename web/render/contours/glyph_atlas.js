// The digits of contour labels as a texture, drawn once from a 2D canvas: dark figures with a
// light halo, so they read on any ground colour. Drawn in GL (not a DOM overlay) so screenshots,
// which render into an offscreen framebuffer, carry them.

/** The characters a label can hold, in atlas order. */
export const GLYPHS = '0123456789-.';
/** Pixels of one glyph's cell in the atlas. */
export const CELL_W = 28, CELL_H = 40;
/** A glyph's advance as a share of its cell's width (the figures are narrower than the cell). */
export const ADVANCE = 0.62;

/** Glyph indices of a height's label text: integers plain, fractions with up to two decimals. */
export function labelGlyphs(height) {
  const text = Number.isInteger(height) ? String(height) : String(Number(height.toFixed(2)));
  return [...text].map((c) => GLYPHS.indexOf(c)).filter((k) => k >= 0);
}

/** @param {WebGL2RenderingContext} gl @param {number} unit the texture unit it is bound on */
export function makeGlyphAtlas(gl, unit) {
  const g = textCanvas(CELL_W * GLYPHS.length, CELL_H, Math.round(CELL_H * 0.7));
  g.textAlign = 'center';
  for (let k = 0; k < GLYPHS.length; ++k) {
    const x = (k + 0.5) * CELL_W, y = CELL_H * 0.54;
    g.strokeStyle = 'rgba(255, 250, 235, 0.9)';
    g.lineWidth = 7;
    g.strokeText(GLYPHS[k], x, y);
    g.fillStyle = 'rgb(60, 32, 10)';
    g.fillText(GLYPHS[k], x, y);
  }
  return textTexture(gl, unit, g.canvas);
}

/** A 2D canvas's context for text: bold sans-serif of `fontPx`, centred on its line, round joins for halos. */
export function textCanvas(width, height, fontPx) {
  const canvas = typeof OffscreenCanvas === 'function' ? new OffscreenCanvas(width, height)
    : Object.assign(document.createElement('canvas'), { width, height });
  const g = canvas.getContext('2d');
  g.font = `bold ${fontPx}px sans-serif`;
  g.textBaseline = 'middle';
  g.lineJoin = 'round';
  return g;
}

/** A canvas of text as a texture on `unit`: premultiplied (halos blend right), mipmapped, clamped. */
export function textTexture(gl, unit, canvas) {
  const texture = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, true);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, canvas);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
  gl.generateMipmap(gl.TEXTURE_2D);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  return texture;
}

/**
 * Draws `count` instanced screen-space quads (a triangle strip each) of the program and VAO in
 * use, over everything (no depth test), blending a premultiplied atlas, then puts back the
 * state the terrain's drawing expects.
 */
export function drawTextQuads(gl, count) {
  gl.disable(gl.DEPTH_TEST);
  gl.disable(gl.CULL_FACE);
  gl.enable(gl.BLEND);
  gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
  gl.drawArraysInstanced(gl.TRIANGLE_STRIP, 0, 4, count);
  gl.disable(gl.BLEND);
  gl.enable(gl.DEPTH_TEST);
  gl.bindVertexArray(null);
}
