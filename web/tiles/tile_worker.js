// A module Web Worker that reads and decodes COG tiles off the main thread, for the pool of
// worker_tile_reader.js; the protocol is tile_service.js's.
import { serveTiles } from './tile_service.js';

serveTiles(self);
