#!/usr/bin/env node
// Prints the slowest tests from the JSON lines of lib/test_time_reporter.js.
//   node scripts/test_times.js COUNT FILE...
import { readFileSync, existsSync } from 'node:fs';
import { relative } from 'node:path';

const [count, ...files] = process.argv.slice(2);
const tests = files.filter((file) => existsSync(file)).flatMap((file) => readFileSync(file, 'utf8').split('\n').filter(Boolean)
  .map((line) => JSON.parse(line)));
tests.sort((a, b) => b.ms - a.ms);
console.log(`the ${Math.min(Number(count), tests.length)} slowest of ${tests.length} tests:`);
for (const t of tests.slice(0, Number(count))) {
  console.log(`  ${(t.ms / 1000).toFixed(1).padStart(6)} s  ${relative(process.cwd(), t.file)}: ${t.name}`);
}
