// hexlod profile: the height profile along a polyline over a height field, with the page's
// loaders, WASM core and measuring library (web/measure/): prints the summary and writes the
// samples as CSV.
import { writeFileSync } from 'node:fs';
import { UsageError, parseOptions, parseNumber, loadForCommand, FILE_OPTIONS, FILE_USAGE, parseFileOptions } from './cli_common.js';
import { fieldSampler } from '../web/measure/field_sampler.js';
import { computeProfile } from '../web/measure/profile.js';
import { computeTrackProfile } from '../web/measure/track_profile.js';
import { readOverlay } from '../web/overlays/read_overlay.js';
import { placeOverlay } from '../web/overlays/place_overlay.js';
import { trackLines } from '../web/overlays/track_lines.js';
import { OverlayError } from '../web/overlays/overlay_error.js';
import { useNodeCrsDefinitions } from './crs_definitions.js';
import { readNamedFile } from './image_files.js';
import { profileCsv } from '../web/measure/profile_csv.js';
import { geoCoordinates, formatCoordinates, crsToLocal } from '../web/geo/coordinates.js';
import { formatLength } from '../web/measure/units.js';

export const PROFILE_SHORT_USAGE = 'usage: hexlod profile <heightfield> (--line X0,Y0,X1,Y1[,...] [--crs] | --track FILE [--feature N]) [--csv OUT] [--step M]';
export const PROFILE_USAGE = `${PROFILE_SHORT_USAGE}
  The height profile along a polyline: heights of the full-resolution samples (bilinear between
  them) every --step metres and at every vertex. Prints its length on the map and along the
  ground, climb, descent, lowest and highest height and slopes; parts of the line off the field
  are left out, and it says how much.
  --line X0,Y0,X1,Y1,...  the polyline's points: metres from the first sample, x east and y south
                        (the page's z), or with --crs in the file's CRS (easting,northing or
                        lon,lat degrees)
  --crs                 --line is in the file's CRS (the file must have a georeference)
  --track FILE          the profile along a track of a GPX, KML, KMZ or GeoJSON file instead
                        (the height field must have a georeference): every vertex of it is a
                        sample, beside the file's own elevations and times; adds the recorded
                        climb, the time and the mean and moving speeds
  --feature N           which line of the file (default 1, the first); the lines are listed
  --step M              metres between samples (default: the field's finer sample spacing)
  --csv OUT             write the samples as CSV: distance_m, x_m, z_m, the CRS coordinates
                        when the file has them, height_m (for a track also gps_elevation_m,
                        time and vertex); the summary as '# ' lines on top
${FILE_USAGE}`;

const OPTIONS = { line: 'string', track: 'string', feature: 'string', csv: 'string', step: 'string', crs: 'boolean', ...FILE_OPTIONS };

/** Checks the command line and turns it into settings; throws UsageError. */
export function profileSettings(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return { help: true };
  if (positionals.length !== 1) throw new UsageError('profile takes exactly one height field file');
  if (values.line === undefined && values.track === undefined) throw new UsageError('profile needs --line X0,Y0,X1,Y1[,...] or --track FILE');
  if (values.line !== undefined && values.track !== undefined) throw new UsageError('profile takes --line or --track, not both');
  if (values.track !== undefined && values.crs) throw new UsageError('--crs is for --line: a track carries its own coordinates');
  if (values.feature !== undefined && values.track === undefined) throw new UsageError('--feature picks a line of --track FILE');
  return {
    file: positionals[0],
    line: values.line !== undefined ? parseLine(values.line) : null,
    track: values.track ?? null,
    feature: values.feature !== undefined ? parseNumber('feature', values.feature, { min: 1, integer: true }) : 1,
    crs: values.crs === true,
    step: values.step !== undefined ? parseNumber('step', values.step, { min: 0, exclusiveMin: true }) : undefined,
    csv: values.csv ?? null,
    fileOptions: parseFileOptions(values),
  };
}

/** 'x0,y0,x1,y1,...' -> [[x0, y0], [x1, y1], ...]; throws UsageError. */
export function parseLine(text) {
  const parts = text.split(',');
  const bad = parts.find((p) => p.trim() === '' || !Number.isFinite(Number(p)));
  if (bad !== undefined) throw new UsageError(`--line must be numbers X0,Y0,X1,Y1,...: '${bad.trim()}' is not a number`);
  if (parts.length % 2 !== 0) throw new UsageError(`--line needs X,Y pairs, got ${parts.length} numbers`);
  if (parts.length < 4) throw new UsageError(`--line needs at least 2 points (4 numbers), got ${parts.length}`);
  const numbers = parts.map(Number), points = [];
  for (let k = 0; k < numbers.length; k += 2) points.push([numbers[k], numbers[k + 1]]);
  return points;
}

export async function profile(args) {
  const settings = profileSettings(args);
  if (settings.help) {
    console.log(PROFILE_USAGE);
    return;
  }
  const { terrain, field, spacingX, spacingY } = await loadForCommand(settings.file, null, settings.fileOptions);
  const georef = field.georef ?? null;
  if (settings.track) {
    trackProfile(settings, { terrain, field, spacingX, spacingY, georef }, await readTrack(settings.track, georef, terrain));
    terrain.destroy();
    return;
  }
  let points = settings.line;
  if (settings.crs) {
    if (!georef) throw new UsageError(`--crs: ${field.source} has no georeference (no CRS); give --line in metres from its first sample`);
    points = points.map(([cx, cy]) => crsToLocal(georef, cx, cy, spacingX, spacingY));
  }
  let result;
  try {
    result = computeProfile(points, fieldSampler(terrain, georef), { step: settings.step });
  } catch (error) {
    throw new UsageError(`--line: ${error.message}`);
  }
  const s = result.summary, n = result.samples.distance.length;
  const signed = (v) => `${v.toFixed(1)} m`;
  const lines = [
    `file      ${field.source} (${terrain.width} x ${terrain.height} samples, ${spacingX} x ${spacingY} m)`,
    `line      ${points.length} points`,
    `length    ${formatLength(s.length)} on the map, ${formatLength(s.length3d)} along the ground`,
    `climb     gain ${signed(s.gain)}, loss ${signed(s.loss)}`,
    `heights   ${s.min.toFixed(1)} .. ${s.max.toFixed(1)} m`,
    `slope     mean ${s.meanSlope.toFixed(1)}°, steepest ${s.steepestSlope.toFixed(1)}° (between samples)`,
    `samples   ${n}, every ${formatLength(result.step)} at most`,
  ];
  if (georef) {
    const { x, z } = result.samples;
    lines.push(`from      ${formatCoordinates(geoCoordinates(georef, x[0], z[0], spacingX, spacingY))}`);
    lines.push(`to        ${formatCoordinates(geoCoordinates(georef, x[n - 1], z[n - 1], spacingX, spacingY))}`);
  }
  finish(lines, result, settings.csv, georef, spacingX, spacingY);
  terrain.destroy();
}

/** The lines every profile ends with (what was clipped, notes, the CSV written), printed. */
function finish(lines, result, csv, georef, spacingX, spacingY) {
  if (result.clipped) lines.push(`clipped   ${result.clipped}`);
  if (result.note) lines.push(`note      ${result.note}`);
  if (csv) {
    writeFileSync(csv, profileCsv(result, georef, spacingX, spacingY));
    lines.push(`csv       ${csv} (${result.samples.distance.length} rows)`);
  }
  console.log(lines.join('\n'));
}

/** Reads and places the track file's lines; throws UsageError with the overlay's message. */
async function readTrack(file, georef, terrain) {
  useNodeCrsDefinitions();
  let named;
  try {
    named = await readNamedFile(file, 'track');
  } catch (error) {
    throw new UsageError(`--track ${error.message}`); // names the file
  }
  try {
    const overlay = await readOverlay(named.name, named.bytes);
    const placed = placeOverlay(overlay, georef, { columns: terrain.width, rows: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY });
    const lines = trackLines(placed);
    if (lines.length === 0) throw new OverlayError('it has no line (a track, route or LineString) to profile');
    return { overlay, lines };
  } catch (error) {
    if (error instanceof OverlayError) throw new UsageError(`--track ${file}: ${error.message}`);
    throw error;
  }
}

/** The profile of one line of a track file: the summary, the file's lines listed, the CSV. */
function trackProfile(settings, { terrain, field, spacingX, spacingY, georef }, { overlay, lines }) {
  if (settings.feature > lines.length) throw new UsageError(`--feature ${settings.feature}: ${settings.track} has ${lines.length} line${lines.length === 1 ? '' : 's'}`);
  const line = lines[settings.feature - 1];
  let result;
  try {
    result = computeTrackProfile(line.placed, line.source, fieldSampler(terrain, georef), { step: settings.step });
  } catch (error) {
    throw new UsageError(`--track ${settings.track}: line ${settings.feature}${line.feature.name ? ` (${line.feature.name})` : ''}: ${error.message}`);
  }
  const s = result.summary, n = result.samples.distance.length;
  const vertices = result.samples.vertex.reduce((count, v) => count + (v >= 0 ? 1 : 0), 0);
  const out = [
    `file      ${field.source} (${terrain.width} x ${terrain.height} samples, ${spacingX} x ${spacingY} m)`,
    `track     ${overlay.name} (${overlay.format}), line ${settings.feature} of ${lines.length}: ${line.feature.name ?? 'unnamed'}, ${line.placed.x.length} points`,
    ...(lines.length > 1 ? lines.map((l, k) => `  ${k === settings.feature - 1 ? '*' : ' '} ${k + 1}  ${l.feature.name ?? 'unnamed'} (${l.feature.source}, ${l.placed.x.length} points${l.onTerrain === 'none' ? ', off the terrain' : ''})`) : []),
    `length    ${formatLength(s.length)} on the map, ${formatLength(s.length3d)} along the ground`,
    `climb     gain ${s.gain.toFixed(1)} m, loss ${s.loss.toFixed(1)} m (terrain)` +
      (Number.isFinite(s.gpsGain) ? `; recorded gain ${s.gpsGain.toFixed(1)} m, loss ${s.gpsLoss.toFixed(1)} m` : ''),
    `heights   ${s.min.toFixed(1)} .. ${s.max.toFixed(1)} m`,
    `slope     mean ${s.meanSlope.toFixed(1)}°, steepest ${s.steepestSlope.toFixed(1)}° (between samples)`,
  ];
  if (s.duration !== null) {
    out.push(`time      ${(s.duration / 3600).toFixed(2)} h; mean speed ${(s.averageSpeed * 3.6).toFixed(2)} km/h` +
      (s.movingSpeed !== null ? `, moving ${(s.movingSpeed * 3.6).toFixed(2)} km/h` : ''));
  }
  out.push(`samples   ${n} (${vertices} vertices of the track on the field), every ${formatLength(result.step)} at most between them`);
  finish(out, result, settings.csv, georef, spacingX, spacingY);
}
