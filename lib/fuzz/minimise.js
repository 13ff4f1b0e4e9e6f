// Shrinks a failing input while it keeps failing the same way: delta debugging by removal
// (Zeller's ddmin, complements only). A format that can take its file apart (PNG into chunks,
// TIFF into directory entries and blocks, an ASCII grid into rows) is shrunk first part by
// part, written back whole each time, so that chunk lengths, CRCs and offsets stay right;
// then the bytes themselves, through the format's repair (PNG CRCs rewritten).

const without = (b, start, end) => {
  const out = new Uint8Array(b.length - (end - start));
  out.set(b.subarray(0, start));
  out.set(b.subarray(end), start);
  return out;
};

/** ddmin over a byte array: removes ever smaller runs, last first, while `fails` holds. */
async function ddmin(bytes, fails) {
  let best = bytes, n = 2;
  while (best.length >= 1) {
    const size = Math.ceil(best.length / n);
    let removed = false;
    for (let start = best.length - size; start > -size; start -= size) {
      const candidate = without(best, Math.max(0, start), start + size);
      if (await fails(candidate)) {
        best = candidate;
        n = Math.max(n - 1, 2);
        removed = true;
        break;
      }
    }
    if (!removed) {
      if (size <= 1) break;
      n = Math.min(n * 2, best.length);
    }
  }
  return best;
}

/**
 * @param {Uint8Array} bytes
 * @param {(candidate: Uint8Array) => Promise<boolean>} fails true when the candidate still fails the same way
 * @param {{ split?: (bytes: Uint8Array) => ({ parts: Array<Uint8Array|null>, join: Function, shrinkInside: boolean } | null),
 *   repair?: (bytes: Uint8Array) => Uint8Array, budget: { tests: number } }} options budget.tests is
 *   decremented by every test; at 0 the search stops
 * @returns {Promise<Uint8Array>} the smallest failing input found
 */
export async function minimiseBytes(bytes, fails, { split, repair = (b) => b, budget }) {
  const test = async (candidate) => {
    if (budget.tests <= 0) return false;
    budget.tests--;
    return fails(candidate);
  };
  let best = bytes;
  const structure = split?.(best);
  if (structure && await test(structure.join(structure.parts))) {
    const { parts, join } = structure;
    best = join(parts);
    // Whole parts first, last first; then inside each part, the largest first.
    for (let i = parts.length - 1; i >= 0; i--) {
      const saved = parts[i];
      parts[i] = null;
      if (await test(join(parts))) best = join(parts); else parts[i] = saved;
    }
    if (structure.shrinkInside) {
      const order = parts.map((p, i) => i).filter((i) => parts[i]).sort((a, b) => parts[b].length - parts[a].length);
      for (const i of order) {
        parts[i] = await ddmin(parts[i], (candidate) => {
          const saved = parts[i];
          parts[i] = candidate;
          const joined = join(parts);
          parts[i] = saved;
          return test(joined);
        });
        best = join(parts);
      }
    }
  }
  return ddmin(best, (candidate) => test(repair(candidate))).then((b) => (b === best ? best : repair(b)));
}

/**
 * Minimises every file of a case in turn (the height field, then its sidecar).
 * @param {Array<{ name: string, bytes: Uint8Array }>} files
 * @param {(files: Array<{ name: string, bytes: Uint8Array }>) => Promise<boolean>} fails
 * @returns {Promise<{ files: Array<{ name: string, bytes: Uint8Array }>, tests: number }>}
 */
export async function minimiseFiles(files, fails, { format, maxTests = 3000 }) {
  const budget = { tests: maxTests };
  let current = files.map((f) => ({ ...f }));
  for (let k = 0; k < current.length; k++) {
    const main = k === 0;
    const bytes = await minimiseBytes(current[k].bytes, (candidate) => fails(current.map((f, i) => (i === k ? { ...f, bytes: candidate } : f))),
      { split: main ? format.split : undefined, repair: main ? format.repair : undefined, budget });
    current = current.map((f, i) => (i === k ? { ...f, bytes } : f));
  }
  return { files: current, tests: maxTests - budget.tests };
}
