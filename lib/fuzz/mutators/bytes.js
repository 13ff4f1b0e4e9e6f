// Generic byte-level mutations, applied on top of the structure-aware ones: bit flips, random
// bytes, insertions, deletions, duplicated runs, truncation, and splices with another seed of
// the same format. They know nothing of the format, so they mostly test its first checks.

/**
 * @param {Uint8Array} bytes
 * @param {import('../random.js').Random} random
 * @param {Uint8Array[]} others other seeds of the format, for splices
 * @returns {[Uint8Array, string]} the mutated copy and what was done
 */
export function mutateBytes(bytes, random, others = []) {
  const n = bytes.length;
  const at = () => random.int(n + 1);
  const join = (...parts) => {
    const out = new Uint8Array(parts.reduce((s, p) => s + p.length, 0));
    let p = 0;
    for (const part of parts) { out.set(part, p); p += part.length; }
    return out;
  };
  const kind = random.weighted([[4, 'flip'], [3, 'set'], [2, 'insert'], [2, 'delete'], [1, 'duplicate'],
    [2, 'truncate'], [1, 'splice'], [1, 'head']]);
  switch (kind) {
    case 'flip': {
      const out = bytes.slice(), k = random.range(1, 8);
      for (let i = 0; i < k && n; i++) out[random.int(n)] ^= 1 << random.int(8);
      return [out, `flip ${k} bits`];
    }
    case 'set': {
      const out = bytes.slice(), k = random.range(1, 4);
      for (let i = 0; i < k && n; i++) out[random.int(n)] = random.pick([0, 0xff, 0x7f, 0x80, random.int(256)]);
      return [out, `set ${k} bytes`];
    }
    case 'head': { // headers live in the first bytes
      const out = bytes.slice(), k = random.range(1, 3);
      for (let i = 0; i < k && n; i++) out[random.int(Math.min(n, 64))] = random.int(256);
      return [out, `set ${k} header bytes`];
    }
    case 'insert': {
      const p = at(), extra = Uint8Array.from({ length: random.smallLength() }, () => random.int(256));
      return [join(bytes.subarray(0, p), extra, bytes.subarray(p)), `insert ${extra.length} at ${p}`];
    }
    case 'delete': {
      const p = at(), len = random.smallLength();
      return [join(bytes.subarray(0, p), bytes.subarray(p + len)), `delete ${len} at ${p}`];
    }
    case 'duplicate': {
      const p = at(), len = random.smallLength();
      return [join(bytes.subarray(0, p + len), bytes.subarray(p, p + len), bytes.subarray(p + len)), `duplicate ${len} at ${p}`];
    }
    case 'truncate': {
      const p = at();
      return [bytes.slice(0, p), `truncate at ${p}`];
    }
    default: { // splice: our head, another seed's tail
      if (!others.length) return [bytes.slice(0, at()), 'truncate'];
      const other = random.pick(others), p = at(), q = random.int(other.length + 1);
      return [join(bytes.subarray(0, p), other.subarray(q)), `splice at ${p} with another seed from ${q}`];
    }
  }
}
