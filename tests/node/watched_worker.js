// Runs a fuzz worker with a per-case watchdog: the worker posts { start: description } before
// each case and { done: summary } at the end; a case that takes longer than perCaseMs (a
// decoder stuck in a loop) terminates it and fails with that case's description.
import { Worker } from 'node:worker_threads';

/**
 * @param {URL} url the worker module (usually the test file itself)
 * @param {object} workerData
 * @param {number} perCaseMs
 * @returns {Promise<object>} the worker's summary
 */
export function runWatchedWorker(url, workerData, perCaseMs) {
  return new Promise((resolve, reject) => {
    const worker = new Worker(url, { workerData });
    let timer = null, current = null;
    worker.on('message', (m) => {
      clearTimeout(timer);
      if (m.start) {
        current = m.start;
        timer = setTimeout(() => {
          worker.terminate();
          reject(new Error(`fuzz case ${current} did not finish within ${perCaseMs} ms`));
        }, perCaseMs);
      } else if (m.done) {
        resolve(m.done);
      }
    });
    worker.on('error', reject);
    worker.on('exit', (code) => {
      clearTimeout(timer);
      if (code !== 0) reject(new Error(`fuzz worker exited with ${code} during ${current}`));
    });
  });
}
