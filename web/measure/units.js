// Lengths and areas as people read them: metres below a kilometre, kilometres above.

/** '850 m', '1.25 km', '12.3 km'. */
export function formatLength(metres) {
  const m = Math.abs(metres);
  if (m < 1000) return `${Number(metres.toPrecision(m < 10 ? 2 : 3))} m`;
  return `${(metres / 1000).toFixed(m < 10000 ? 2 : 1)} km`;
}

/** '850 m²', '1.25 km²'. */
export function formatArea(squareMetres) {
  const a = Math.abs(squareMetres);
  if (a < 1e6) return `${Number(squareMetres.toPrecision(a < 10 ? 2 : 3))} m²`;
  return `${(squareMetres / 1e6).toFixed(a < 1e7 ? 2 : 1)} km²`;
}
