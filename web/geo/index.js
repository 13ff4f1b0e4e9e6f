// Geography and TIFF reading, the public face of web/geo/: coordinate reference systems and
// georeferences, world files, real coordinates of samples, and the TIFF reader that height
// fields, draped images and COG tiles share. Other folders import this module only;
// the decoders behind the TIFF reader register themselves once (tiff_open.js).
export * from './georef.js';
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
