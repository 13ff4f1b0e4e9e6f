#!/usr/bin/env node
// The npm package: figures printed, never asserted. Packs the project as `npm pack` does (its
// prepack builds the WebAssembly cores and the site first: up to date, they take seconds),
// prints the tarball's size packed and unpacked and its file count, then installs the tarball
// N times, each into a new empty folder (a package.json of a project that uses hexlod), with no
// compiler on PATH, and prints the median, the fastest and the slowest install and the size of
// what an install puts in node_modules. Every install runs with npm's cache warm (this script's
// first install fills it from the registry if `npm ci` has not) and --prefer-offline, so the
// figure is npm's own work (resolving, unpacking, linking), not the network's.
//
//   node bench/package.js [--installs N]   (default 5)
import { mkdtempSync, rmSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { quantile } from '../lib/cli_common.js';
import { countOption } from '../lib/script_options.js';
import { INSTALL_FLAGS, folderSize, installTarball, packProject } from '../lib/packed_install.js';

const USAGE = 'usage: node bench/package.js [--installs N]\n  N installs of the packed tarball into empty folders (default 5)';
const { count: installs, exitCode } = countOption('bench/package.js', USAGE, 'installs', 5);
if (installs === null) process.exit(exitCode);

const mb = (bytes) => `${(bytes / 1e6).toFixed(2)} MB`;
const work = mkdtempSync(join(tmpdir(), 'hexlod-bench-package-'));
try {
  const pack = await packProject(work);
  console.log(`package   ${pack.tarball.split('/').pop()}: ${mb(pack.size)} packed, ${mb(pack.unpackedSize)} unpacked, ${pack.files.length} files`);
  const times = [];
  let installed = null;
  for (let k = 0; k < installs; k++) {
    const dir = join(work, `install-${k}`);
    times.push(await installTarball(pack.tarball, dir));
    installed ??= folderSize(join(dir, 'node_modules'));
    rmSync(dir, { recursive: true, force: true });
  }
  const s = (ms) => `${(ms / 1000).toFixed(2)} s`;
  console.log(`install   median ${s(quantile(times, 0.5))} of ${times.length} (fastest ${s(Math.min(...times))}, slowest ${s(Math.max(...times))}), ` +
    `npm install ${INSTALL_FLAGS.join(' ')} TARBALL into an empty folder, npm's cache warm, no compiler on PATH`);
  console.log(`installed node_modules ${mb(installed.bytes)} in ${installed.files} files (hexlod and its runtime dependencies)`);
  console.log(`machine   ${cpus().length} cores (${cpus()[0]?.model ?? '?'}), Node ${process.version}; load average ${loadavg().map((l) => l.toFixed(2)).join(' ')}`);
} finally {
  rmSync(work, { recursive: true, force: true });
}
