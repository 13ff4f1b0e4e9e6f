// LZW and deflate TIFF blocks through our decoders (tiff_lzw.js, tiff_deflate.js) instead of
// the geotiff library's: the same code that counted every block before anything was allocated
// (tiff_blocks.js) decodes it. The library's registry is global: importing this module once
// registers them for every reader (height fields and draped images).

import { addDecoder } from 'geotiff';
import { TiffLzwDecoder } from './tiff_lzw.js';
import { TiffDeflateDecoder } from './tiff_deflate.js';
import { decoderParametersOf } from './tiff_blocks.js';

addDecoder(5, async () => TiffLzwDecoder, decoderParametersOf, false);
addDecoder([8, 32946], async () => TiffDeflateDecoder, decoderParametersOf, false);
