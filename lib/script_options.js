// The command line of a benchmark script (node bench/NAME.js [options]): its options, or the
// exit code it ends with at once, with the usage printed as every script prints it.
import { UsageError } from './cli_common.js';

/**
 * Parses a script's arguments with `parse`, which returns the options, or null for --help, and
 * throws a UsageError for a mistake.
 * @param {string} name the script's name, which starts the line of a usage mistake
 * @param {string} usage its usage text
 * @param {(args: string[]) => object|null} parse
 * @param {string[]} [args] the arguments (default: the process's)
 * @returns {{options: object} | {options: null, exitCode: number}} the options; or none and the
 *   exit code: 0 after printing the usage on stdout for --help, 2 after printing the mistake and
 *   the usage on stderr
 */
export function scriptOptions(name, usage, parse, args = process.argv.slice(2)) {
  let options;
  try {
    options = parse(args);
  } catch (error) {
    if (!(error instanceof UsageError)) throw error;
    console.error(`${name}: ${error.message}\n${usage}`);
    return { options: null, exitCode: 2 };
  }
  if (!options) {
    console.log(usage);
    return { options: null, exitCode: 0 };
  }
  return { options };
}
