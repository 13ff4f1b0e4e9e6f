#!/usr/bin/env node
// hexlod command line: the page's loaders and WASM core, in Node.
//   hexlod info <file> [--json]   size, spacing, height range and load time of a height field
import { readFileSync, existsSync, statSync } from 'node:fs';
import { basename, extname, join, dirname } from 'node:path';
import { parseArgs } from 'node:util';
import { createNodeCore } from './node_core.js';
import { loadTerrain } from '../web/terrain_source.js';

const USAGE = `usage: hexlod info <heightfield> [--json]
  A .png or .f32 file; a .json sidecar with the same name beside it is read too.`;

class UsageError extends Error {}

/** The file and, when one sits beside it, its .json sidecar, as loader inputs. */
function readInputs(path) {
  if (!existsSync(path)) throw new Error(`${path}: no such file`);
  if (!statSync(path).isFile()) throw new Error(`${path}: not a file`);
  const files = [{ name: basename(path), bytes: new Uint8Array(readFileSync(path)) }];
  const sidecar = join(dirname(path), basename(path, extname(path)) + '.json');
  if (extname(path).toLowerCase() !== '.json' && existsSync(sidecar)) {
    files.push({ name: basename(sidecar), bytes: new Uint8Array(readFileSync(sidecar)) });
  }
  return files;
}

async function info(args) {
  const { values, positionals } = parseArgs({ args, options: { json: { type: 'boolean' } }, allowPositionals: true });
  if (positionals.length !== 1) throw new UsageError('info takes exactly one height field file');
  const core = await createNodeCore();
  const { terrain, field, missing, loadMs } = await loadTerrain(core, readInputs(positionals[0]));
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
    loadMs: Number(loadMs.toFixed(1)),
  };
  if (values.json) {
    console.log(JSON.stringify(report, null, 1));
    return;
  }
  const spacingNote = field.spacingFromFile ? 'from the file' : 'assumed: the file gives none';
  console.log([
    `file     ${report.file} (${report.format}, ${report.sampleType})`,
    `size     ${report.width} x ${report.height} samples`,
    `spacing  ${report.spacingX} x ${report.spacingY} m (${spacingNote})`,
    `heights  ${report.minHeight.toFixed(2)} .. ${report.maxHeight.toFixed(2)} m`,
    `missing  ${missing} samples filled`,
    `load     ${report.loadMs} ms`,
  ].join('\n'));
}

const commands = { info };

async function main(argv) {
  const [command, ...rest] = argv;
  if (!command || command === '--help' || command === '-h') {
    console.log(USAGE);
    return 0;
  }
  if (!commands[command]) throw new UsageError(`unknown command '${command}'`);
  await commands[command](rest);
  return 0;
}

main(process.argv.slice(2)).then((code) => { process.exitCode = code; }, (error) => {
  // One clear line on stderr; usage mistakes also get the usage text.
  console.error(`hexlod: ${error.message}`);
  if (error instanceof UsageError || error.code?.startsWith?.('ERR_PARSE_ARGS')) {
    console.error(USAGE);
    process.exitCode = 2;
  } else {
    process.exitCode = 1;
  }
});
