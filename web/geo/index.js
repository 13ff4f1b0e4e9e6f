// Geography and TIFF reading, the public face of web/geo/: coordinate reference systems (their
// EPSG definitions, WKT, transforms between them) and georeferences, world files and the
// other sidecars, real coordinates of samples, and the TIFF reader that height fields, draped
// images and COG tiles share. Other folders import this module only; the decoders behind the
// TIFF reader register themselves once (tiff_open.js).
export * from './georef.js';
export * from './crs_definitions.js';
export * from './crs_transform.js';
export * from './crs_wkt.js';
export * from './crs_error.js';
export * from './aux_xml.js';
export * from './crs_sidecars.js';
export * from './sidecar_names.js';
export * from './coordinates.js';
export * from './world_file.js';
export * from './ground_spacing.js';
export * from './shown.js';
export * from './tiff_open.js';
export * from './tiff_fields.js';
export * from './tiff_directory.js';
export * from './tiff_library.js';
export * from './tiff_blocks.js';
export * from './tiff_raster.js';
export * from './tiff_georef.js';
export * from './tiff_jpeg_stream.js';
export { inflate, isInflateError } from './inflate.js';
export * from './warp_grid.js';
export * from './earth_frame.js';
export * from './earth_shape.js';
