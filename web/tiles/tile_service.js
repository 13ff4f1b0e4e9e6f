// The tile reading done in a worker: a COG opened by the worker itself, tiles read and decoded
// there and their samples sent back without a copy. Kept apart from the worker script so any
// message port can serve it (a Web Worker's global scope, or one end of a MessageChannel in the
// Node tests).
//
// Messages to the service:
//   { type: 'open', input: string | Blob, options: { retries?, backoffMs?, name? } }
//   { type: 'read', id, level, tx, ty }
//   { type: 'cancel', id }              aborts the read of that id (it then answers 'failed')
// Answers, in the order the work ends:
//   { type: 'opened', info }            info: what the pool publishes of the COG (infoOf)
//   { type: 'open-failed', error }
//   { type: 'tile', id, samples, stats }   samples' buffer transferred
//   { type: 'failed', id, error, stats }
// error: { name, kind?, message, status?, size? } (see errorToMessage); stats: the worker's
// reader's { requests, bytes } so far. Every read gets exactly one answer, cancelled or not.

import { openCog } from './cog_source.js';
import { TileError } from './tile_error.js';

/**
 * Answers the messages of a port until it closes.
 * @param {{ postMessage: (message: unknown, transfer?: Transferable[]) => void,
 *   onmessage: ((event: { data: any }) => void) | null }} port a worker's global scope or a MessagePort
 * @param {typeof openCog} [open] how to open the COG
 */
export function serveTiles(port, open = openCog) {
  let source = null;
  const reading = new Map(); // id -> AbortController

  port.onmessage = async ({ data }) => {
    if (data.type === 'open') {
      try {
        source = open(data.input, data.options ?? {});
        port.postMessage({ type: 'opened', info: infoOf(await source) });
      } catch (e) {
        source = null;
        port.postMessage({ type: 'open-failed', error: errorToMessage(e) });
      }
    } else if (data.type === 'read') {
      const controller = new AbortController();
      reading.set(data.id, controller);
      let cog = null;
      try {
        if (!source) throw new Error('no COG open in this tile worker');
        cog = await source;
        const samples = await cog.readTile(data.level, data.tx, data.ty, controller.signal);
        port.postMessage({ type: 'tile', id: data.id, samples, stats: { ...cog.stats } }, [samples.buffer]);
      } catch (e) {
        port.postMessage({ type: 'failed', id: data.id, error: errorToMessage(e), stats: cog ? { ...cog.stats } : null });
      } finally {
        reading.delete(data.id);
      }
    } else if (data.type === 'cancel') {
      reading.get(data.id)?.abort();
    }
  };
}

/**
 * What a pool needs to stand in for the CogSource: its descriptive fields, all cloneable.
 * @param {import('./cog_source.js').CogSource} cog
 */
export function infoOf(cog) {
  return {
    name: cog.name, width: cog.width, height: cog.height, sampleType: cog.sampleType, nodata: cog.nodata,
    georef: cog.georef, spacingX: cog.spacingX, spacingY: cog.spacingY, tileWidth: cog.tileWidth,
    tileHeight: cog.tileHeight, levels: cog.levels, hasOverviews: cog.hasOverviews, size: cog.size,
    statistics: cog.statistics, heightScale: cog.heightScale, heightOffset: cog.heightOffset,
    stats: { ...cog.stats },
  };
}

/** An error as a message: a TileError keeps its kind, status and size; others their name. */
export function errorToMessage(e) {
  const error = { name: e?.name ?? 'Error', message: String(e?.message ?? e) };
  if (e instanceof TileError) {
    error.kind = e.kind;
    if (e.status !== undefined) error.status = e.status;
    if (e.size !== undefined) error.size = e.size;
  }
  return error;
}

/** The error a message stands for: a TileError of the same kind, a RangeError, or an Error. */
export function errorFromMessage(error) {
  if (error.kind !== undefined) {
    const details = {};
    if (error.status !== undefined) details.status = error.status;
    if (error.size !== undefined) details.size = error.size;
    return new TileError(error.kind, error.message, details);
  }
  if (error.name === 'RangeError') return new RangeError(error.message);
  const plain = new Error(error.message);
  plain.name = error.name;
  return plain;
}
