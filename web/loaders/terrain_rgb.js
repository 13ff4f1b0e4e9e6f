// Heights encoded in the colour channels of an 8-bit RGB(A) PNG, as web map tiles carry them.
//   Terrain-RGB (Mapbox): h = -10000 + (R * 65536 + G * 256 + B) * 0.1   (0.1 m steps)
//   Terrarium (Mapzen / AWS Terrain Tiles): h = R * 256 + G + B / 256 - 32768   (1/256 m steps)

/** Decoders by encoding name: (r, g, b) -> metres. */
export const ENCODINGS = {
  'terrain-rgb': (r, g, b) => -10000 + (r * 65536 + g * 256 + b) * 0.1,
  terrarium: (r, g, b) => r * 256 + g + b / 256 - 32768,
};

/** Heights of real terrain (Dead Sea floor to above Everest, sea floor included). */
const PLAUSIBLE_M = [-11500, 9000];

/** The encoding a file name announces ('terrarium', 'terrain-rgb', 'terrainrgb', 'mapbox'), or null. */
export function encodingFromName(name) {
  const n = name.toLowerCase();
  if (n.includes('terrarium')) return 'terrarium';
  if (/terrain[-_ ]?rgb|mapbox/.test(n)) return 'terrain-rgb';
  return null;
}

/**
 * Guesses the encoding from one row of pixels: the one under which every pixel is a plausible
 * height. The two cannot both fit (Terrain-RGB needs R <= 2, Terrarium R >= 83).
 * @param {Uint8Array} pixels row bytes, `channels` per pixel, RGB first
 * @returns {string|null} an encoding name, or null when neither fits
 */
export function detectEncoding(pixels, channels) {
  for (const [encoding, decode] of Object.entries(ENCODINGS)) {
    let fits = true;
    for (let i = 0; i + 2 < pixels.length && fits; i += channels) {
      const h = decode(pixels[i], pixels[i + 1], pixels[i + 2]);
      fits = h >= PLAUSIBLE_M[0] && h <= PLAUSIBLE_M[1];
    }
    if (fits) return encoding;
  }
  return null;
}
