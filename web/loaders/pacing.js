// Chunked decoding: a loader writes its samples straight into the caller's array (WASM memory)
// a band of rows at a time and, between bands, gives the event loop back so the page keeps
// drawing and can paint a progress bar. A worker is no option here: the core's memory is not
// shared with workers, so a worker would decode into a full-size copy of its own.
//
// While the loader waits, the page may call the core and WASM memory may grow, which detaches
// every view on the old buffer: after each pause the sink asks for a fresh view.

import { allocateSamples } from './common.js';

/** Work between pauses, in milliseconds: short enough to keep frames flowing. */
const SLICE_MS = 24;

const now = () => (typeof performance !== 'undefined' ? performance.now() : Date.now());

/** Resolves on the next macrotask (setImmediate in Node, a MessageChannel in browsers). */
function nextTask() {
  if (typeof setImmediate === 'function') return new Promise((resolve) => setImmediate(resolve));
  return new Promise((resolve) => {
    const channel = new MessageChannel();
    channel.port1.onmessage = () => { channel.port1.close(); resolve(); };
    channel.port2.postMessage(0);
  });
}

/**
 * The destination of one decode: the array from allocate() plus the pacing.
 * Loaders read `sink.samples` again after every `await sink.pace(...)`.
 */
export class SampleSink {
  /**
   * @param {Function} allocate the caller's allocate(sampleType, width, height)
   * @param {'u8'|'u16'|'i16'|'f32'} sampleType
   * @param {number} width
   * @param {number} height
   * @param {{ onProgress?: (fraction: number) => void, reacquire?: () => ArrayLike<number> }} [options]
   *   onProgress gets 0..1 at each pause; reacquire returns a fresh view on the same samples
   *   (needed when they live in memory that may grow)
   */
  constructor(allocate, sampleType, width, height, options = {}) {
    this.samples = allocate ? allocateSamples(allocate, sampleType, width, height) : null;
    this.onProgress = options.onProgress ?? null;
    this.reacquire = options.reacquire ?? null;
    this.sliceStart = now();
  }

  /** A sink over samples that are already allocated (for passes after the decode). */
  static over(samples, options = {}) {
    const sink = new SampleSink(null, null, 0, 0, options);
    sink.samples = samples;
    return sink;
  }

  /** True when the current slice of work is used up (cheap; call it often). */
  due() {
    return now() - this.sliceStart >= SLICE_MS;
  }

  /**
   * Pauses when the slice is used up: reports progress, yields, refreshes the view.
   * @param {number} fraction of the work done, 0..1
   */
  async pace(fraction) {
    if (!this.due()) return;
    this.onProgress?.(fraction);
    await nextTask();
    if (this.reacquire) this.samples = this.reacquire();
    this.sliceStart = now();
  }
}

/**
 * Pauses for work done before anything is allocated (a file proving its declared size): the
 * same slices as a SampleSink, with progress but no samples to reacquire.
 * @param {(fraction: number) => void} [onProgress]
 * @returns {(fraction: number) => Promise<void>}
 */
export function pacer(onProgress) {
  const sink = SampleSink.over(null, { onProgress });
  return (fraction) => sink.pace(fraction);
}
