// A drop's files (web/ui/dropped_files.js): files as they come; a folder read through the
// entries API as a browser gives it (entries in batches, asynchronously, until an empty batch),
// its folders too, sorted by name, hidden files left out, and a folder too big to be one
// terrain's stopped at MAX_DROPPED_FILES.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { droppedFiles, MAX_DROPPED_FILES } from '../../web/ui/dropped_files.js';

const file = (name) => ({ name, isFile: true, isDirectory: false, file: (ok) => setTimeout(() => ok({ name }), 0) });
function folder(name, children, batch = 2) {
  return { name, isFile: false, isDirectory: true, createReader() {
    let at = 0;
    return { readEntries: (ok) => setTimeout(() => { ok(children.slice(at, at + batch)); at += batch; }, 0) };
  } };
}
const transfer = (entries, files = []) => ({ files, items: entries.map((entry) => ({ kind: 'file', webkitGetAsEntry: () => entry })) });
const names = async (t) => (await droppedFiles(t)).files.map((f) => f.name);

test('files alone come as the drop gives them; without the entries API too', async () => {
  const files = [{ name: 'b.tif' }, { name: 'a.prj' }];
  assert.deepEqual(await droppedFiles(transfer([file('b.tif'), file('a.prj')], files)), { files, truncated: false });
  assert.deepEqual(await droppedFiles({ files, items: [{ kind: 'file' }] }), { files, truncated: false });
  assert.deepEqual(await droppedFiles(null), { files: [], truncated: false });
});

test('a folder is its files and its folders\' files, by name, read in batches, hidden files left out', async () => {
  const survey = folder('survey', [file('dem.tif'), file('.DS_Store'), folder('ortho', [file('ortho.pgw'), file('ortho.png'), file('ortho.prj')], 1),
    file('dem.tif.aux.xml'), file('README.txt')]);
  assert.deepEqual(await names(transfer([survey, file('extra.jpg')])),
    ['README.txt', 'dem.tif', 'dem.tif.aux.xml', 'ortho.pgw', 'ortho.png', 'ortho.prj', 'extra.jpg']);
});

test('a folder of more files than one terrain has is stopped and says so', async () => {
  const many = folder('disk', Array.from({ length: MAX_DROPPED_FILES + 5 }, (_, i) => file(`f${String(i).padStart(5, '0')}.tif`)), 500);
  const { files, truncated } = await droppedFiles(transfer([many]));
  assert.deepEqual([files.length, truncated], [MAX_DROPPED_FILES, true]);
});
