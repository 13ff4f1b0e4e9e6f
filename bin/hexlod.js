#!/usr/bin/env node
// hexlod command line (lib/cli.js). Before it is loaded, this checks what it needs that a clone
// does not hold until it is set up and built: the npm packages and the WebAssembly core. A
// missing piece gets one line saying what to run, and exit code 2, instead of a module error.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const missing = [];
let packages = true;
try {
  import.meta.resolve('geotiff'); // one of the runtime packages, wherever npm put them
} catch {
  packages = false;
  missing.push('the npm packages');
}
const builds = ['build/wasm', 'build/wasm-diag']
  .filter((dir) => !existsSync(`${root}${dir}/hexlod_core.mjs`) || !existsSync(`${root}${dir}/hexlod_core.wasm`));
if (builds.length) missing.push(`the WebAssembly core (${builds.join(', ')})`);
if (missing.length) {
  const fix = packages ? './build.sh' : 'scripts/setup.sh && ./build.sh';
  console.error(`hexlod: ${missing.join(' and ')} ${missing.length > 1 ? 'are' : 'is'} missing: run ${fix}`);
  process.exit(2);
}
const { runCli } = await import('../lib/cli.js');
await runCli(process.argv.slice(2));
