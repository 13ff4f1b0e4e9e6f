// The measured line in the address bar: written rounded to a tenth of the field's spacing, read
// back as the same points, and every bad value refused with a message that says what is wrong.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { measureParam, parseMeasureParam } from '../../web/ui/measure_tool.js';
import { parseUrlState } from '../../web/app/url_state.js';

test('a path and an area round-trip through their measure= value', () => {
  const path = [[1234.567, 89.01], [2000, 3000.44]];
  assert.equal(measureParam('path', path, 5), 'p:1234.6,89;2000,3000.4');
  assert.equal(measureParam('path', path, 30), 'p:1235,89;2000,3000');
  assert.equal(measureParam('path', path, 900), 'p:1235,89;2000,3000');
  assert.deepEqual(parseMeasureParam('p:1234.6,89;2000,3000.4'), { kind: 'path', points: [[1234.6, 89], [2000, 3000.4]] });
  const area = [[0, 0], [10.123, 0], [0, 10.5]];
  assert.deepEqual(parseMeasureParam(measureParam('area', area, 1)), { kind: 'area', points: [[0, 0], [10.1, 0], [0, 10.5]] });
});

test('bad measure= values are refused with the reason', () => {
  const refusals = {
    'x:1,2;3,4': /must start with p: .* or a:/,
    'p:1,2': /a path needs at least 2 points/,
    'a:1,2;3,4': /an area needs at least 3 points/,
    'p:1,2;abc,4': /'abc,4' is not an x,z pair/,
    'p:1,2;3': /'3' is not an x,z pair/,
    'p:1,2;3,4,5': /'3,4,5' is not an x,z pair/,
    'p:1,2;1e12,4': /not an x,z pair/,
    'p:1,2;,4': /not an x,z pair/,
  };
  for (const [text, reason] of Object.entries(refusals)) {
    const result = parseMeasureParam(text);
    assert.ok(result instanceof Error, text);
    assert.match(result.message, reason, text);
  }
  const state = parseUrlState('?measure=p:1,2&tau=2');
  assert.equal(state.measure, null);
  assert.match(state.errors[0], /^measure=p:1,2: a path needs at least 2 points/);
  assert.deepEqual(parseUrlState('?measure=a:0,0;5,0;0,5').measure, { kind: 'area', points: [[0, 0], [5, 0], [0, 5]] });
});
