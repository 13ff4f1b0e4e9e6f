// The command line of a benchmark script (node bench/NAME.js [options]): its options, or the
// exit code it ends with at once, with the usage printed as every script prints it.
import { UsageError, parseOptions, parseNumber } from './cli_common.js';

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

/**
 * The command line of a script whose only option is one count (--NAME N, a whole number ≥ 1),
 * e.g. how many runs a benchmark makes: the count, or the exit code as scriptOptions gives it.
 * @param {string} script the script's name
 * @param {string} usage its usage text
 * @param {string} name the option's name, without its dashes
 * @param {number} fallback the count without the option
 * @param {string[]} [args] the arguments (default: the process's)
 * @returns {{count: number} | {count: null, exitCode: number}}
 */
export function countOption(script, usage, name, fallback, args = process.argv.slice(2)) {
  const { options, exitCode } = scriptOptions(script, usage, (given) => {
    const { values, positionals } = parseOptions(given, { [name]: 'string' });
    if (values.help) return null;
    if (positionals.length) throw new UsageError(`unexpected argument ${positionals[0]}`);
    return { count: values[name] === undefined ? fallback : parseNumber(name, values[name], { integer: true, min: 1 }) };
  }, args);
  return options ? { count: options.count } : { count: null, exitCode };
}
