// hexlod profile: the height profile along a polyline over a height field, with the page's
// loaders, WASM core and measuring library (web/measure/): prints the summary and writes the
// samples as CSV.
import { writeFileSync } from 'node:fs';
import { UsageError, parseOptions, parseNumber, loadForCommand, FILE_OPTIONS, FILE_USAGE, parseFileOptions } from './cli_common.js';
import { fieldSampler } from '../web/measure/field_sampler.js';
import { computeProfile } from '../web/measure/profile.js';
import { profileCsv } from '../web/measure/profile_csv.js';
import { geoCoordinates, formatCoordinates, crsToLocal } from '../web/geo/coordinates.js';
import { formatLength } from '../web/measure/units.js';

export const PROFILE_SHORT_USAGE = 'usage: hexlod profile <heightfield> --line X0,Y0,X1,Y1[,...] [--csv OUT] [--step M] [--crs]';
export const PROFILE_USAGE = `${PROFILE_SHORT_USAGE}
  The height profile along a polyline: heights of the full-resolution samples (bilinear between
  them) every --step metres and at every vertex. Prints its length on the map and along the
  ground, climb, descent, lowest and highest height and slopes; parts of the line off the field
  are left out, and it says how much.
  --line X0,Y0,X1,Y1,...  the polyline's points: metres from the first sample, x east and y south
                        (the page's z), or with --crs in the file's CRS (easting,northing or
                        lon,lat degrees)
  --crs                 --line is in the file's CRS (the file must have a georeference)
  --step M              metres between samples (default: the field's finer sample spacing)
  --csv OUT             write the samples as CSV: distance_m, x_m, z_m, the CRS coordinates
                        when the file has them, height_m; the summary as '# ' lines on top
${FILE_USAGE}`;

const OPTIONS = { line: 'string', csv: 'string', step: 'string', crs: 'boolean', ...FILE_OPTIONS };

/** Checks the command line and turns it into settings; throws UsageError. */
export function profileSettings(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return { help: true };
  if (positionals.length !== 1) throw new UsageError('profile takes exactly one height field file');
  if (values.line === undefined) throw new UsageError('profile needs --line X0,Y0,X1,Y1[,...]');
  return {
    file: positionals[0],
    line: parseLine(values.line),
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
  if (result.clipped) lines.push(`clipped   ${result.clipped}`);
  if (result.note) lines.push(`note      ${result.note}`);
  if (settings.csv) {
    writeFileSync(settings.csv, profileCsv(result, georef, spacingX, spacingY));
    lines.push(`csv       ${settings.csv} (${n} rows)`);
  }
  console.log(lines.join('\n'));
  terrain.destroy();
}
