// The loop of every format's mutate(): one to three of the format's steps, picked by weight,
// applied in turn to the case's state.

/** How many steps a case takes, [weight, count]: one most often, three least. */
export const STEP_COUNTS = [[6, 1], [3, 2], [1, 3]];

/**
 * Applies steps to `state` and returns what they did, in order.
 * @param {object} state the case being made, which the steps change
 * @param {import('../random.js').Random} random
 * @param {Array<[number, (state: object, random: object) => string|null]>} steps [weight, step]
 *   entries; a step returns what it did, or null when it did nothing
 * @param {{counts?: Array<[number, number]>, lastVerdict?: boolean}} [options] counts: the
 *   weights of how many steps; lastVerdict: state.invalid (a step's claim that the file must be
 *   refused) is cleared before each step, since a later step may repair the file
 * @returns {string[]}
 */
export function applySteps(state, random, steps, { counts = STEP_COUNTS, lastVerdict = false } = {}) {
  const how = [];
  for (let k = random.weighted(counts); k > 0; k--) {
    const [, step] = random.weighted(steps.map((entry) => [entry[0], entry]));
    if (lastVerdict) state.invalid = null;
    const done = step(state, random);
    if (done) how.push(done);
  }
  return how;
}
