// The lines of a placed overlay one can profile or fly along: every path of every line feature
// (a GPX track's segments, a route, a LineString), in file order, each with its place on the
// terrain and the file's own values (elevations, times).

/**
 * @param {ReturnType<import('./place_overlay.js').placeOverlay>} placed
 * @returns {Array<{feature: object, placed: {x: Float64Array, z: Float64Array, inside: Uint8Array},
 *   source: import('./geojson_features.js').Path, onTerrain: 'all'|'part'|'none'}>}
 */
export function trackLines(placed) {
  return placed.features.flatMap(({ feature, paths, onTerrain }) => (feature.kind !== 'line' ? []
    : paths.map((path, p) => ({ feature, placed: path, source: feature.paths[p], onTerrain }))));
}
