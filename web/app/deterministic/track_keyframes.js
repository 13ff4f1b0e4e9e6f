// The keyframes of a flight along a track (flight.js "track"): the file read and placed on the
// terrain as the page places overlays, the line it names, and the camera path along it
// (overlays/track_flight.js). The page and `hexlod regress` in Node both call this, each with
// the file's bytes and the same WASM core's heights, so both fly the same camera.
import { readOverlay } from '../../overlays/read_overlay.js';
import { placeOverlay } from '../../overlays/place_overlay.js';
import { trackKeyframes } from '../../overlays/track_flight.js';
import { trackLines } from '../../overlays/track_lines.js';

/**
 * @param {{file: string, height: number, speed: number|null, lookAhead: number, line: number}} track the flight's
 * @param {{name: string, bytes: Uint8Array}} file the track file
 * @param {{width: number, height: number, spacingX: number, spacingY: number, heightAt: (x: number, z: number) => number}} terrain
 * @param {import('../../geo/georef.js').Georef|null} georef the terrain's, its CRS resolved
 * @returns {Promise<Array<{time: number, position: number[], target: number[], fov: number}>>}
 * @throws {Error} a file that cannot be read, a terrain it cannot be placed on, no such line, a line off the terrain
 */
export async function flightTrackKeyframes(track, file, terrain, georef) {
  const overlay = await readOverlay(file.name, file.bytes);
  const placed = placeOverlay(overlay, georef, { columns: terrain.width, rows: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY });
  const lines = trackLines(placed);
  if (lines.length === 0) throw new Error(`${file.name}: no line (track, route or LineString) to fly along`);
  if (track.line > lines.length) throw new Error(`${file.name}: "track".line ${track.line}, but it has ${lines.length} line${lines.length === 1 ? '' : 's'}`);
  const line = lines[track.line - 1];
  if (line.onTerrain === 'none') throw new Error(`${file.name}: line ${track.line} lies entirely off the terrain`);
  const extentX = (terrain.width - 1) * terrain.spacingX, extentZ = (terrain.height - 1) * terrain.spacingY;
  return trackKeyframes(line.placed, line.source, (x, z) => terrain.heightAt(x, z),
    { height: track.height, lookAhead: track.lookAhead, speed: track.speed, extentX, extentZ });
}
