// A worker thread with a per-case watchdog and a memory watch. The worker posts { start: key }
// before each case, any other messages while it works, and { done: true } when the job is
// finished. A case that runs longer than caseMs (a decoder stuck in a loop), a worker that
// dies (an uncaught error, a JS heap past its limit) and a process whose resident memory grows
// more than memoryCapBytes during one case stop the job: the worker is terminated, the job's
// promise says which case stopped it and how, and the next job starts a fresh worker.
import { Worker } from 'node:worker_threads';
import { memoryUsage } from 'node:process';

const POLL_MS = 50;
/** Time a case may take per megabyte of input, beyond caseMs: a valid 26 MB SRTM tile with
 *  scattered voids takes seconds to load on a busy machine, and a hang is a loop, not a big file. */
export const MS_PER_MB = 400;

/** The time limit of a case of `bytes` bytes of input. */
export function caseLimitMs(caseMs, bytes) {
  return Math.round(caseMs + ((bytes ?? 0) / 2 ** 20) * MS_PER_MB);
}

export class WatchedWorker {
  /**
   * @param {URL} url the worker module
   * @param {{ caseMs?: number, memoryCapBytes?: number, heapMb?: number, workerData?: any }} [options]
   *   caseMs: time limit of one case; memoryCapBytes: growth of the process's resident memory
   *   allowed during one case; heapMb: the worker's JS heap limit (old generation)
   */
  constructor(url, { caseMs = 5000, memoryCapBytes = 2 ** 31, heapMb = 1024, workerData = {} } = {}) {
    // workerData must be an object: geotiff imports web-worker, which destructures it in any
    // worker thread it finds itself in.
    Object.assign(this, { url, caseMs, memoryCapBytes, heapMb, workerData, worker: null });
  }

  /**
   * Posts one job and waits for its end.
   * @param {any} job the message to the worker
   * @param {(message: any) => void} onMessage gets every message other than start and done
   * @returns {Promise<null | { kind: 'hang'|'died'|'memory', key: any, error?: Error, ms: number, limitMs: number }>} null
   *   when the job finished, else what stopped it during case `key` (undefined: between cases)
   * @throws when a fresh worker dies before its first case: the worker itself is broken
   */
  run(job, onMessage) {
    if (!this.worker) {
      const worker = new Worker(this.url, { workerData: this.workerData, resourceLimits: { maxOldGenerationSizeMb: this.heapMb } });
      worker.on('error', (e) => { worker.error = e; });
      worker.on('exit', () => worker.onExit?.());
      this.worker = worker;
    }
    const worker = this.worker;
    return new Promise((resolve, reject) => {
      let key, started = 0, rssAtStart = 0, timer = null, finished = false, limitMs = this.caseMs;
      const poll = setInterval(() => {
        if (key !== undefined && memoryUsage.rss() - rssAtStart > this.memoryCapBytes) stop('memory');
      }, POLL_MS);
      const finish = (result) => {
        if (finished) return;
        finished = true;
        clearTimeout(timer);
        clearInterval(poll);
        worker.off('message', onWorkerMessage);
        worker.onExit = null;
        resolve(result);
      };
      const stop = (kind) => {
        const ms = performance.now() - started;
        this.worker = null;
        worker.terminate();
        finish({ kind, key, error: worker.error, ms, limitMs });
      };
      const onWorkerMessage = (m) => {
        if (m && 'start' in m) {
          worker.started = true;
          key = m.start;
          started = performance.now();
          rssAtStart = memoryUsage.rss();
          clearTimeout(timer);
          limitMs = caseLimitMs(this.caseMs, m.bytes);
          timer = setTimeout(() => stop('hang'), limitMs);
        } else if (m && m.done) {
          finish(null);
        } else {
          if (m && 'result' in m) { clearTimeout(timer); key = undefined; }
          onMessage(m);
        }
      };
      worker.on('message', onWorkerMessage);
      worker.onExit = () => {
        this.worker = null;
        const error = worker.error;
        if (!worker.started) {
          finished = true;
          clearInterval(poll);
          reject(new Error(`the fuzz worker died before its first case: ${error?.stack ?? 'it exited'}`));
          return;
        }
        finish({ kind: error?.code === 'ERR_WORKER_OUT_OF_MEMORY' ? 'memory' : 'died', key, error, ms: performance.now() - started });
      };
      worker.postMessage(job);
    });
  }

  /** Ends the worker (after the last job). */
  async close() {
    const worker = this.worker;
    this.worker = null;
    await worker?.terminate();
  }
}
