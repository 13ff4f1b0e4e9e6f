// The random source of one fuzz case. A case is named by (format, seed, index) and its input is
// made from this generator alone, so any case can be made again by itself (--replay
// png:1:4711) without running the ones before it.
import { seededRandom } from '../../web/app/seeded_random.js';

/** FNV-1a over the text of the case's name: a 32-bit seed per case. */
function hashName(text) {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) h = Math.imul(h ^ text.charCodeAt(i), 0x01000193);
  return h >>> 0;
}

/** Helpers over one seeded stream of uniform floats. */
export class Random {
  constructor(seed) {
    this.next = seededRandom(seed);
  }

  /** The generator of case `index` of `format` in the run with `seed`. */
  static forCase(format, seed, index) {
    return new Random(hashName(`${format}:${seed}:${index}`));
  }

  /** A whole number in [0, n). */
  int(n) {
    return Math.floor(this.next() * n);
  }

  /** A whole number in [lo, hi]. */
  range(lo, hi) {
    return lo + this.int(hi - lo + 1);
  }

  /** True with probability p. */
  chance(p) {
    return this.next() < p;
  }

  pick(list) {
    return list[this.int(list.length)];
  }

  /** Picks one of [weight, value] pairs by weight. */
  weighted(pairs) {
    let r = this.next() * pairs.reduce((sum, [w]) => sum + w, 0);
    for (const [w, v] of pairs) if ((r -= w) < 0) return v;
    return pairs[pairs.length - 1][1];
  }

  /** A byte count that is mostly small: lengths of inserted or deleted runs. */
  smallLength() {
    return this.weighted([[8, 1 + this.int(4)], [3, 1 + this.int(64)], [1, 1 + this.int(4096)]]);
  }
}
