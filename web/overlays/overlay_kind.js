// Which files are overlays (GPX, KML, KMZ, GeoJSON), from their names and first bytes: the drop
// sends them to the overlay stage, not to the height-field loaders. A .json is GeoJSON when its
// first object names a GeoJSON type; a height field's .json sidecar does not.

/** What the file picker offers for overlays. */
export const OVERLAY_EXTENSIONS = ['.gpx', '.kml', '.kmz', '.geojson'];
const GEOJSON_TYPES = /"type"\s*:\s*"(FeatureCollection|Feature|Point|MultiPoint|LineString|MultiLineString|Polygon|MultiPolygon|GeometryCollection)"/;

/**
 * @param {string} name
 * @param {Uint8Array} head the file's first bytes
 * @returns {'gpx'|'kml'|'kmz'|'geojson'|null}
 */
export function overlayKind(name, head) {
  const extension = /\.([^./\\]+)$/.exec(name.toLowerCase())?.[1] ?? '';
  if (extension === 'gpx' || extension === 'kml' || extension === 'kmz' || extension === 'geojson') return extension;
  if (extension === 'json') {
    const text = new TextDecoder().decode(head.subarray(0, 4096)).replace(/^\uFEFF/, '').trimStart();
    return text.startsWith('{') && GEOJSON_TYPES.test(text) ? 'geojson' : null;
  }
  return null;
}
