// How GIS sidecars are named after the file they go with, and which files beside a raster are
// metadata that is not read. The drop (imagery/drop_roles.js), the height-field loaders and the
// command line pair files by these names. World files have their own rules (world_file.js).
//   x.prj          the CRS of x.asc, x.png, x.tif ... (ESRI)
//   x.tif.aux.xml  GDAL's record of x.tif (its CRS, perhaps its geotransform); x.aux.xml too

/** 'prj' | 'aux.xml' | the last extension, lower case ('' without one). */
export function extensionOfName(name) {
  if (/\.aux\.xml$/i.test(name)) return 'aux.xml';
  const dot = name.lastIndexOf('.');
  return dot > 0 ? name.slice(dot + 1).toLowerCase() : '';
}

/** True for a .prj file. */
export const isPrjName = (name) => /\.prj$/i.test(name);

/** True for a GDAL .aux.xml file. */
export const isAuxXmlName = (name) => /\.aux\.xml$/i.test(name);

/** The name without its last extension ('x.tif' -> 'x'), lower case. */
function stem(name) {
  const dot = name.lastIndexOf('.');
  return (dot > 0 ? name.slice(0, dot) : name).toLowerCase();
}

/** Whether a .prj or .aux.xml named `sidecar` goes with the file named `owner`. */
export function sidecarBelongsTo(sidecar, owner) {
  const lower = sidecar.toLowerCase(), ownerLower = owner.toLowerCase();
  if (isPrjName(sidecar)) return stem(lower) === stem(ownerLower);
  if (isAuxXmlName(sidecar)) {
    const base = lower.slice(0, -'.aux.xml'.length);
    return base === ownerLower || base === stem(ownerLower);
  }
  return false;
}

/** The names a file's .prj and .aux.xml may have, in the order they are looked for. */
export function crsSidecarNames(owner) {
  const dot = owner.lastIndexOf('.');
  const base = dot > 0 ? owner.slice(0, dot) : owner;
  return { prj: [`${base}.prj`], auxXml: [`${owner}.aux.xml`, `${base}.aux.xml`] };
}

// Files that travel with rasters and hold nothing to show: what each is, for the note that
// says it was skipped.
const METADATA = {
  ovr: 'GeoTIFF overviews', rrd: 'ERDAS overviews', aux: 'ERDAS statistics', msk: 'GDAL mask',
  xml: 'metadata', qmd: 'QGIS metadata', qml: 'QGIS style', sld: 'style', lyr: 'ArcGIS layer', lyrx: 'ArcGIS layer',
  cpg: 'code page', md5: 'checksum', sha1: 'checksum', sha256: 'checksum', sha512: 'checksum',
  vat: 'attribute table', dbf: 'attribute table', ini: 'settings',
};

/** What a metadata file beside a raster is ('GeoTIFF overviews'), or null for any other file. */
export function metadataKind(name) {
  if (isAuxXmlName(name)) return null;
  const lower = name.toLowerCase();
  if (lower.endsWith('.vat.dbf')) return METADATA.vat;
  return METADATA[extensionOfName(name)] ?? null;
}
