// The README's "Use it in your page" shows code the tests run: each of its blocks is a part of
// the example file it names (examples/, which tests/browser/api.test.js and package_page.test.js
// serve and tsc checks), so the README cannot drift from what works.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const root = new URL('../../', import.meta.url);
const readme = readFileSync(new URL('README.md', root), 'utf8');
const start = readme.indexOf('## Use it in your page');
const section = readme.slice(start, readme.indexOf('\n## ', start + 1));

test('every code block of "Use it in your page" is part of the example file named before it', () => {
  const blocks = [...section.matchAll(/^```(\w+)\n([\s\S]*?)^```$/gm)];
  assert.ok(blocks.length >= 5, `the section has its blocks (${blocks.length})`);
  for (const block of blocks) {
    const before = section.slice(0, block.index);
    // The nearest file named before the block, of the block's kind (html or js).
    const names = [...before.matchAll(/`(examples\/[\w./-]+)`|`([\w-]+\.(?:js|html))`/g)]
      .map((m) => m[1] ?? `examples/${m[2]}`)
      .filter((name) => name.endsWith(block[1] === 'html' ? '.html' : '.js'));
    assert.ok(names.length, `a file is named before the ${block[1]} block at ${block.index}`);
    const file = names.at(-1);
    const text = readFileSync(new URL(file, root), 'utf8');
    assert.ok(text.includes(block[2]), `the README's ${block[1]} block is part of ${file}:\n${block[2]}`);
  }
});
