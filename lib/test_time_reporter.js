// A node:test reporter that writes one JSON line per top-level test: its file, name, duration
// and outcome. ./hexlod.sh test runs it beside the usual reporter and prints each layer's time
// and the slowest tests from its lines (scripts/test_times.js).
export default async function* testTimes(source) {
  for await (const event of source) {
    if (event.type !== 'test:pass' && event.type !== 'test:fail') continue;
    const { name, nesting, file, details } = event.data;
    if (nesting !== 0 || details?.duration_ms === undefined) continue;
    yield `${JSON.stringify({ file: file ?? '', name, ms: Math.round(details.duration_ms), passed: event.type === 'test:pass' })}\n`;
  }
}
