// hexlod command line: the page's loaders and WASM core, in Node (started by bin/hexlod.js).
//   hexlod info <file> [--json]   size, spacing, height range and load time of a height field
//   hexlod mesh <file> ...        refine (max error or camera), write OBJ and JSON (lib/mesh_command.js)
//   hexlod bench <file> ...       a scripted flight, and @mapbox/martini on the same data (lib/bench_command.js)
//   hexlod regress <file> <flight> ...  flights in headless Chromium and Node against references (lib/regress.js)
//   hexlod profile <file> --line ...    the height profile along a polyline, as a summary and CSV (lib/profile_command.js)
import { createNodeCore } from './node_core.js';
import { UsageError, readInputs, parseOptions, FILE_OPTIONS, FILE_USAGE, parseFileOptions, loadFiles } from './cli_common.js';
import { mesh, MESH_USAGE } from './mesh_command.js';
import { bench, BENCH_USAGE } from './bench_command.js';
import { regress, REGRESS_USAGE } from './regress.js';
import { profile, PROFILE_USAGE, PROFILE_SHORT_USAGE } from './profile_command.js';
import { useNodeCrsDefinitions } from './crs_definitions.js';
import { geoCoordinates, formatCoordinates } from '../web/geo/coordinates.js';

const INFO_USAGE = `usage: hexlod info <heightfield> [--json] [--width N --height N] [--encoding E]
  A height field: PNG (16/8-bit grayscale, Terrain-RGB, Terrarium), GeoTIFF (.tif), SRTM .hgt,
  ESRI .asc, PGM (P5), RAW/R16 (.r16, .raw), or .f32; a .json sidecar with the same name beside
  it is read too (required for .f32), and so are its .prj and GDAL .aux.xml (its CRS). Prints
  its CRS (EPSG code and name) and the latitude and longitude of its centre when it has one.
${FILE_USAGE}`;
const USAGE = [INFO_USAGE, MESH_USAGE, BENCH_USAGE, REGRESS_USAGE, PROFILE_USAGE].join('\n\n');
// The one line a usage mistake ends with, per command.
const SHORT_USAGE = {
  info: 'usage: hexlod info <heightfield> [--json] [--width N --height N] [--encoding E]',
  mesh: 'see hexlod mesh --help',
  bench: 'see hexlod bench --help',
  regress: 'see hexlod regress --help',
  profile: PROFILE_SHORT_USAGE,
  '': 'usage: hexlod info|mesh|bench|regress|profile <heightfield> [options]; see hexlod --help',
};

async function info(args) {
  const { values, positionals } = parseOptions(args, { json: 'boolean', ...FILE_OPTIONS });
  if (values.help) { console.log(INFO_USAGE); return; }
  if (positionals.length !== 1) throw new UsageError('info takes exactly one height field file');
  const fileOptions = parseFileOptions(values);
  const core = await createNodeCore();
  const { terrain, field, missing, loadMs } = await loadFiles(core, readInputs(positionals[0]), fileOptions);
  const report = {
    file: field.source,
    format: field.format,
    sampleType: field.sampleType,
    width: terrain.width,
    height: terrain.height,
    spacingX: field.spacingX,
    spacingY: field.spacingY,
    spacingFromFile: field.spacingFromFile,
    minHeight: terrain.minHeight,
    maxHeight: terrain.maxHeight,
    missingSamples: missing,
    crs: crsReport(field, terrain),
    notes: field.notes ?? [],
    loadMs: Number(loadMs.toFixed(1)),
  };
  if (values.json) {
    console.log(JSON.stringify(report, null, 1));
    return;
  }
  const spacingNote = field.spacingFromFile ? 'from the file' : 'assumed: the file gives none';
  const { crs } = report;
  console.log([
    `file     ${report.file} (${report.format}, ${report.sampleType})`,
    `size     ${report.width} x ${report.height} samples`,
    `spacing  ${report.spacingX} x ${report.spacingY} m (${spacingNote})`,
    `heights  ${report.minHeight.toFixed(2)} .. ${report.maxHeight.toFixed(2)} m`,
    `missing  ${missing} samples filled`,
    `crs      ${crs ? `${crs.label}${crs.name && crs.name !== crs.label ? ` ${crs.name}` : ''}${crs.definition ? '' : ' (no definition: no latitude and longitude)'}` : 'none (local metres)'}`,
    ...(crs ? [`centre   ${crs.centreText}`] : []),
    ...report.notes.map((note) => `note     ${note}`),
    `load     ${report.loadMs} ms`,
  ].join('\n'));
}

/** The field's CRS for info: code, name, whether it has a definition, and its centre's coordinates. */
function crsReport(field, terrain) {
  const georef = field.georef;
  if (!georef) return null;
  const { crs } = georef;
  const at = geoCoordinates(georef, ((terrain.width - 1) / 2) * terrain.spacingX, ((terrain.height - 1) / 2) * terrain.spacingY,
    terrain.spacingX, terrain.spacingY);
  return { epsg: crs.epsg, label: crs.label, name: crs.name, geographic: crs.geographic, definition: crs.proj4 !== null,
    centre: { x: at.easting ?? at.lon, y: at.northing ?? at.lat, lat: at.lat, lon: at.lon }, centreText: formatCoordinates(at) };
}

const commands = { info, mesh, bench, regress, profile };
let current = '';

async function main(argv) {
  const [command, ...rest] = argv;
  if (!command || command === '--help' || command === '-h') {
    console.log(USAGE);
    return 0;
  }
  if (!Object.hasOwn(commands, command)) throw new UsageError(`unknown command '${command}'`);
  current = command;
  const code = await commands[command](rest); // regress returns its own exit code (0-3)
  return typeof code === 'number' ? code : 0;
}

/** Runs the command line on `argv` (the words after `hexlod`); sets process.exitCode. */
export function runCli(argv) {
  useNodeCrsDefinitions(); // EPSG codes resolve from the definitions packages on disk
  // A reader that stops early (hexlod bench --verbose | head) is not an error.
  process.stdout.on('error', (error) => {
    if (error.code === 'EPIPE') process.exit(process.exitCode ?? 0);
    throw error;
  });
  return main(argv).then((code) => { process.exitCode = code; }, (error) => {
    // One clear line on stderr, never a stack trace: usage mistakes (exit 2) end with the
    // command's usage, bad files and core failures (exit 1) name what was wrong.
    const message = String(error?.message ?? error).replace(/\s*\n\s*/g, ' ');
    if (error instanceof UsageError || error?.code?.startsWith?.('ERR_PARSE_ARGS')) {
      console.error(`hexlod: ${message}; ${SHORT_USAGE[current]}`);
      process.exitCode = 2;
    } else {
      console.error(`hexlod: ${message}`);
      process.exitCode = 1;
    }
  });
}
