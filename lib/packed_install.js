// The npm package as a user gets it: `npm pack` of this project (its prepack builds what the
// tarball needs), then `npm install` of the tarball into an empty folder, run with a PATH that
// holds no compiler, so that nothing can be built on the way. The package tests and the
// package benchmark share it; packAndInstall() reuses an install of the same tarball (by its
// sha256), so several test files of one run pay for one install.
import { execFile } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, renameSync, rmSync, statSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, delimiter, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const projectDir = fileURLToPath(new URL('..', import.meta.url));
/** Flags of every install: no audit or funding requests (the registry alone is reachable), the warm cache first. */
export const INSTALL_FLAGS = ['--prefer-offline', '--no-audit', '--no-fund'];
/** Programs a package install may use to build native code: none is on noCompilerPath(). */
export const COMPILERS = ['em++', 'emcc', 'cmake', 'cc', 'gcc', 'c++', 'g++', 'clang', 'make'];
// What node, npm, npx and the scripts npm runs need (npm runs a package's bin through sh).
const TOOLS = ['node', 'npm', 'npx', 'sh', 'env'];

/** The path of a program on PATH, or null. */
export function which(program, path = process.env.PATH ?? '') {
  for (const dir of path.split(delimiter)) {
    const file = join(dir, program);
    if (dir && existsSync(file) && statSync(file).isFile()) return file;
  }
  return null;
}

/** A folder holding links to node, npm, npx and sh only: a PATH on which no compiler is found. */
export function noCompilerPath() {
  const dir = join(tmpdir(), `hexlod-nocc-bin-${process.pid}`);
  if (!existsSync(dir)) {
    mkdirSync(dir);
    process.once('exit', () => rmSync(dir, { recursive: true, force: true }));
    for (const tool of TOOLS) {
      const found = tool === 'node' ? process.execPath : which(tool);
      if (!found) throw new Error(`${tool} is not on PATH`);
      symlinkSync(found, join(dir, tool));
    }
  }
  return dir;
}

/** The environment of a command that must do without a compiler: PATH is noCompilerPath(). */
export function noCompilerEnv(extra = {}) {
  return { ...process.env, PATH: noCompilerPath(), ...extra };
}

/** Runs a program; resolves with { code, stdout, stderr, ms } (never rejects for an exit code). */
export function run(program, args, { cwd, env = process.env, timeout = 600000 } = {}) {
  const start = performance.now();
  return new Promise((resolve) => {
    execFile(program, args, { cwd, env, timeout, maxBuffer: 64 << 20 }, (error, stdout, stderr) => {
      resolve({ code: error ? (error.code ?? error.signal) : 0, stdout, stderr, ms: performance.now() - start });
    });
  });
}

async function mustRun(what, program, args, options) {
  const result = await run(program, args, options);
  if (result.code !== 0) throw new Error(`${what} failed (${result.code}):\n${result.stdout}\n${result.stderr}`);
  return result;
}

/**
 * `npm pack` of the project into `dir` (its prepack script builds the WebAssembly and the site).
 * @returns {Promise<{tarball: string, size: number, unpackedSize: number, files: string[], sha256: string}>}
 */
export async function packProject(dir = mkdtempSync(join(tmpdir(), 'hexlod-pack-'))) {
  const { stdout } = await mustRun('npm pack', 'npm', ['pack', '--json', '--pack-destination', dir], { cwd: projectDir });
  // The prepack build prints before npm's JSON: the JSON is the array at the end.
  const [packed] = JSON.parse(stdout.slice(stdout.lastIndexOf('\n[') + 1));
  const tarball = join(dir, packed.filename);
  return { tarball, size: packed.size, unpackedSize: packed.unpackedSize, files: packed.files.map((f) => f.path),
    sha256: createHash('sha256').update(readFileSync(tarball)).digest('hex') };
}

/**
 * Installs a tarball into `dir` (made empty: a package.json of a project that uses hexlod), with
 * PATH holding no compiler. Returns the install's wall time in milliseconds.
 */
export async function installTarball(tarball, dir) {
  mkdirSync(dir, { recursive: true });
  writeFileSync(join(dir, 'package.json'), `${JSON.stringify({ name: 'uses-hexlod', version: '1.0.0', private: true }, null, 2)}\n`);
  const { ms } = await mustRun('npm install of the tarball', 'npm', ['install', ...INSTALL_FLAGS, tarball], { cwd: dir, env: noCompilerEnv() });
  return ms;
}

/** The size in bytes and the count of the files under a folder. */
export function folderSize(dir) {
  let bytes = 0, files = 0;
  for (const entry of readdirSync(dir, { recursive: true, withFileTypes: true })) {
    if (!entry.isFile()) continue;
    bytes += statSync(join(entry.parentPath ?? entry.path, entry.name)).size;
    files++;
  }
  return { bytes, files };
}

/**
 * Packs the project and installs the tarball into a folder of its own, or reuses the folder of an
 * earlier install of the same tarball (same sha256). Folders of other tarballs older than a day
 * are removed.
 * @returns {Promise<{pack: Awaited<ReturnType<typeof packProject>>, dir: string, installMs: number|null}>}
 *   dir: the project that installed hexlod (its node_modules/hexlod is the package); installMs:
 *   null when the install was reused
 */
export async function packAndInstall() {
  const pack = await packProject();
  const dir = join(tmpdir(), `hexlod-installed-${pack.sha256.slice(0, 16)}`);
  const done = join(dir, '.installed');
  let installMs = null;
  if (!existsSync(done)) {
    // Into a folder of its own first, renamed when complete: a failed or parallel install leaves no half-made folder under the name.
    const building = mkdtempSync(`${dir}-partial-`);
    installMs = await installTarball(pack.tarball, building);
    writeFileSync(join(building, '.installed'), `${pack.tarball}\n`);
    rmSync(dir, { recursive: true, force: true });
    try {
      renameSync(building, dir);
    } catch (error) {
      if (!existsSync(done)) throw error; // another run installed the same tarball meanwhile: use that one
      rmSync(building, { recursive: true, force: true });
    }
  }
  const dayAgo = Date.now() - 86400e3;
  for (const name of readdirSync(tmpdir())) {
    const other = join(tmpdir(), name);
    if (name.startsWith('hexlod-installed-') && other !== dir && statSync(other).mtimeMs < dayAgo) rmSync(other, { recursive: true, force: true });
  }
  // The tarball is kept beside the install it made (a later test may install it elsewhere).
  const kept = join(dir, basename(pack.tarball));
  if (!existsSync(kept)) renameSync(pack.tarball, kept);
  rmSync(dirname(pack.tarball), { recursive: true, force: true });
  return { pack: { ...pack, tarball: kept }, dir, installMs };
}
