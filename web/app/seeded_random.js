// A small seeded pseudo-random generator (mulberry32): the same sequence in every run and
// every JS engine, for scripted camera paths and fuzz tests.

/**
 * @param {number} seed any 32-bit integer
 * @returns {() => number} a function returning floats uniform in [0, 1)
 */
export function seededRandom(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
