// A draped image in one line, for the HUD's list of layers.

/**
 * "image ortho.jpg  8192 × 8192 px, 0.50 m/px, covers 62 % of the field"
 * @param {import('./open_image.js').DrapedImage} image
 */
export function describeImage({ name, width, height, metresPerPixel, placement }) {
  const perPixel = metresPerPixel === null ? '' : `, ${metresPerPixel >= 10 ? metresPerPixel.toFixed(0) : metresPerPixel.toPrecision(2)} m/px`;
  const share = placement.coverage * 100;
  const covers = placement.how === 'stretched' ? 'stretched over the field'
    : `covers ${share >= 99.95 ? '100' : share >= 1 ? share.toFixed(0) : share.toPrecision(1)} % of the field`;
  return `image ${name}  ${width} × ${height} px${perPixel}, ${covers}`;
}
