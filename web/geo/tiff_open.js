// The one way into the geotiff library's files: importing this module registers our LZW and
// deflate decoders (tiff_decoders.js) in the library's global registry, once, before any TIFF
// is opened, for height fields, draped images and COG tiles alike.
import GeoTIFF, { fromArrayBuffer } from 'geotiff';
import './tiff_decoders.js';

/** A TIFF held whole in memory (an ArrayBuffer of exactly its bytes: tiff_library.js fileBuffer). */
export const openTiffBuffer = (buffer) => fromArrayBuffer(buffer);

/** A TIFF read through a geotiff source (HTTP Range requests, a File's slices), cancelled by `signal`. */
export const openTiffSource = (source, signal) => GeoTIFF.fromSource(source, {}, signal);
