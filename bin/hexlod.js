#!/usr/bin/env node
// hexlod command line (lib/cli.js). Before it is loaded, this checks what it needs that may be
// missing: the npm packages and the WebAssembly core. A checkout (src/ is there) holds neither
// until it is set up and built; an installed package ships the core and gets its packages from
// npm, so there a missing piece means a broken install. Either way one line says what to run,
// with exit code 2, instead of a module error.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const checkout = existsSync(`${root}src/api/hexlod.h`);
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
  let fix;
  if (!checkout) fix = `this hexlod package in ${root} is incomplete: reinstall it (npm install hexlod)`;
  else fix = `run ${packages ? './build.sh wasm' : `scripts/setup.sh && ./build.sh${builds.length ? ' wasm' : ''}`}`;
  console.error(`hexlod: ${missing.join(' and ')} ${missing.length > 1 ? 'are' : 'is'} missing: ${fix}`);
  process.exit(2);
}
const { runCli } = await import('../lib/cli.js');
await runCli(process.argv.slice(2));
