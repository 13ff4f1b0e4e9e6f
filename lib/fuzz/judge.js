// The verdict on one case, as the page would meet it: loadTerrain() decodes the files into a
// terrain of the WebAssembly core. A case is
//   refused   a HeightfieldError of one line naming the file, or the core's CoreError of one line;
//   accepted  a terrain whose size is the one the file declares and whose heights are finite;
//   crash     any other exception (a TypeError from a decoder, a WASM trap, a message of several lines);
//   insane    accepted, but with a size other than declared or heights that are not finite, or
//             accepted although the mutation made it invalid for sure (a strip cut short);
//   blow-up   memory the input does not justify: the core asked for more than 4x the input's
//             bytes (+ 1 MiB) for a file it then refused, WASM memory grew at all for a refused
//             file, grew more than 4x the samples for an accepted one, a terrain was left behind,
//             or the core's allocator holds more than 64 KiB more than before the case (a leak;
//             small growth is let pass: the core keeps its last error message, for one); or an
//             accepted field more than 4096x its files + 1 MiB (no codec expands that much: deflate
//             at most 1032x, LZW about 2730x; only a size the data never proved, e.g. sparse blocks);
//             or the worker's JS memory (heap and array buffers, this thread's alone) grew by more
//             than 4x the input + 64 MiB (garbage of the case included: a decoder may make copies).
// Hangs, deaths of the worker and the process's memory are watched from outside (watched_worker.js).
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { HeightfieldError } from '../../web/loaders/index.js';
import { CoreError } from '../../web/core/core.js';

const MIB = 1 << 20;
const MAX_EXPANSION = 4096; // bytes of samples per byte of file, above any codec's
/** This thread's JS memory: in a worker, process.memoryUsage() counts its own isolate's heap and buffers. */
const jsBytes = () => { const m = process.memoryUsage(); return m.heapUsed + m.arrayBuffers; };
const BYTES = { u8: 1, u16: 2, i16: 2, f32: 4 };

/**
 * Counts what the core is asked to allocate: terrains created and the bytes of their samples,
 * and terrains still alive (a refused file must leave none).
 */
export function spyOnCore(core) {
  const spy = { requestedBytes: 0, live: 0, heapInUse: () => 0 };
  const m = core.module;
  if (typeof m._hexlod_diag_heap === 'function') {
    // Bytes allocated and not freed in the core (src/api/hexlod_diagnostics.h), into 16 bytes kept for it.
    const out = m._malloc(16);
    spy.heapInUse = () => (m._hexlod_diag_heap(out) === 0 ? new Float64Array(core.buffer, out, 1)[0] : 0);
  }
  const create = core.createTerrain.bind(core);
  core.createTerrain = (width, height, sampleType) => {
    const terrain = create(width, height, sampleType); // a size the core refuses costs nothing
    spy.requestedBytes += width * height * (BYTES[sampleType] ?? 1);
    spy.live++;
    const destroy = terrain.destroy.bind(terrain);
    terrain.destroy = () => { if (terrain.handle !== 0) spy.live--; destroy(); };
    return terrain;
  };
  return spy;
}

/** A message with its numbers and quoted bits made generic: failures of one kind share it. */
export function signatureOf(message) {
  return String(message).replace(/^[^:]*\.(\w+): /, '*.$1: ').replace(/'[^']*'|"[^"]*"/g, "'…'")
    .replace(/-?\d+(\.\d+)?(e[+-]?\d+)?/gi, 'N').slice(0, 120);
}

/** What is wrong with an accepted terrain, or null. */
function insanity(result, declared) {
  const { terrain, field } = result;
  const problems = [];
  if (!Number.isInteger(field.width) || !Number.isInteger(field.height) || field.width < 1 || field.height < 1) problems.push(`size ${field.width}x${field.height}`);
  // A sparse TIFF loads as its data's extent: the raster it says it was cut from is the declared one, and holds it.
  const whole = field.cropped ?? { column: 0, row: 0, width: field.width, height: field.height };
  if (declared && (declared.width !== whole.width || declared.height !== whole.height)) {
    problems.push(`size ${whole.width}x${whole.height}, declared ${declared.width}x${declared.height}`);
  }
  if (whole.column < 0 || whole.row < 0 || whole.column + field.width > whole.width || whole.row + field.height > whole.height) {
    problems.push(`a ${field.width}x${field.height} field at ${whole.column},${whole.row} of a ${whole.width}x${whole.height} raster`);
  }
  if (terrain.width !== Math.max(field.width, 2) || terrain.height !== Math.max(field.height, 2)) problems.push(`terrain ${terrain.width}x${terrain.height} for a ${field.width}x${field.height} field`);
  if (!Number.isFinite(terrain.minHeight) || !Number.isFinite(terrain.maxHeight) || terrain.minHeight > terrain.maxHeight) {
    problems.push(`heights ${terrain.minHeight}..${terrain.maxHeight}`);
  }
  for (const key of ['spacingX', 'spacingY']) if (!(terrain[key] > 0) || !Number.isFinite(terrain[key])) problems.push(`${key} ${terrain[key]}`);
  if (!Number.isFinite(field.heightScale) || field.heightScale === 0 || !Number.isFinite(field.heightOffset)) problems.push(`height scale ${field.heightScale}, offset ${field.heightOffset}`);
  if (terrain.sampleType === 'f32') {
    const samples = terrain.samples();
    for (let i = 0; i < samples.length; i++) {
      if (!Number.isFinite(samples[i])) { problems.push(`sample ${i} is ${samples[i]}`); break; }
    }
  }
  return problems.length ? problems.join('; ') : null;
}

/** Whether an exception is a clean refusal of the case's files. */
function cleanRefusal(e, files) {
  const oneLine = typeof e.message === 'string' && e.message.length > 0 && !e.message.includes('\n');
  if (e instanceof HeightfieldError) return oneLine && files.some((f) => f.name === e.file) && e.message.startsWith(`${e.file}: `) && e.problem.length > 0;
  if (e instanceof CoreError) return oneLine;
  return false;
}

/**
 * Loads one case into the core and judges it.
 * @returns {Promise<{ kind: string, detail: string, signature: string, ms: number, wasmGrowth: number, jsGrowth: number,
 *   requestedBytes: number, trap: boolean }>}
 */
export async function judgeCase(core, spy, c, declaredSize) {
  const inputBytes = c.files.reduce((s, f) => s + f.bytes.length, 0);
  const wasmBefore = core.buffer.byteLength, jsBefore = jsBytes(), heapBefore = spy.heapInUse();
  spy.requestedBytes = 0;
  const start = performance.now();
  let kind, detail = '', sampleBytes = 0, trap = false;
  try {
    const result = await loadTerrain(core, c.files, c.options);
    const { terrain } = result;
    sampleBytes = terrain.sampleBytes;
    let declared = null;
    try { declared = declaredSize(c.files, c.options); } catch { declared = null; }
    const problem = insanity(result, declared) ?? (c.invalid ? `accepted, but ${c.invalid}` : null);
    kind = problem ? 'insane' : 'accepted';
    detail = problem ?? `${result.field.width}x${result.field.height} ${terrain.sampleType}`;
    terrain.destroy();
  } catch (e) {
    if (e && cleanRefusal(e, c.files)) {
      kind = 'refused';
      detail = e.message;
    } else {
      kind = 'crash';
      trap = e instanceof WebAssembly.RuntimeError;
      const where = String(e?.stack ?? '').split('\n').find((l) => /web\/|node_modules\//.test(l))?.trim() ?? '';
      detail = `${e?.name ?? typeof e}: ${String(e?.message ?? e).split('\n')[0].slice(0, 300)}${where ? ` (${where.replace(/^at /, '').replace(/file:\/\/\S*?\/(web|node_modules)\//, '$1/')})` : ''}`;
    }
  }
  const ms = performance.now() - start;
  const wasmGrowth = core.buffer.byteLength - wasmBefore, jsGrowth = jsBytes() - jsBefore;
  const justified = Math.max(inputBytes, sampleBytes);
  if (kind === 'refused' || kind === 'accepted') {
    const mb = (n) => `${(n / MIB).toFixed(1)} MiB`;
    let blowup = null;
    const held = spy.heapInUse() - heapBefore;
    if (spy.live > 0) blowup = `${spy.live} terrain(s) left allocated in the core`;
    else if (held > 64 * 1024) blowup = `the core holds ${mb(held)} more than before the case (a leak)`;
    else if (kind === 'refused' && spy.requestedBytes > 4 * inputBytes + MIB) blowup = `the core was asked for ${mb(spy.requestedBytes)} for a refused input of ${inputBytes} bytes`;
    else if (kind === 'refused' && wasmGrowth > 0) blowup = `WASM memory grew by ${mb(wasmGrowth)} for a refused input of ${inputBytes} bytes`;
    else if (kind === 'accepted' && sampleBytes > MAX_EXPANSION * inputBytes + MIB) blowup = `a field of ${mb(sampleBytes)} from ${inputBytes} bytes of files`;
    else if (wasmGrowth > 4 * justified + MIB) blowup = `WASM memory grew by ${mb(wasmGrowth)} for ${mb(sampleBytes)} of samples`;
    else if (jsGrowth > 4 * inputBytes + 64 * MIB) blowup = `the worker's JS memory grew by ${mb(jsGrowth)} for an input of ${inputBytes} bytes`;
    if (blowup) { detail = `${blowup} (${kind}: ${detail})`; kind = 'blowup'; }
  }
  return { kind, detail, signature: signatureOf(detail.replace(/ \((refused|accepted): .*$/, '')), ms, wasmGrowth, jsGrowth, requestedBytes: spy.requestedBytes, trap };
}
