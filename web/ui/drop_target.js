// Where files come in by hand: dropped anywhere on the page (files, or a folder as its files),
// or chosen with the Open button's file picker. Both hand the files to one opener as one load.
import { ACCEPT_EXTENSIONS, ACCEPTED } from '../loaders/index.js';
import { IMAGE_EXTENSIONS } from '../imagery/drop_roles.js';
import { OVERLAY_EXTENSIONS } from '../overlays/overlay_kind.js';
import { DRAPED_FORMATS } from '../imagery/image_formats.js';
import { droppedFiles, MAX_DROPPED_FILES } from './dropped_files.js';

/**
 * @param {(files: FileList|File[]) => Promise<string>} openPicked
 * @param {(message: string, isError?: boolean) => void} showStatus
 */
export function installDropTarget(openPicked, showStatus) {
  const picker = document.getElementById('file-input'), button = document.getElementById('open-button');
  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', async (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    const { files, truncated } = await droppedFiles(e.dataTransfer);
    if (truncated) {
      showStatus(`the dropped folder holds more than ${MAX_DROPPED_FILES} files: drop the files of one terrain`, true);
      return;
    }
    if (files.length) await openPicked(files);
  });
  picker.accept = [...ACCEPT_EXTENSIONS, ...IMAGE_EXTENSIONS, ...OVERLAY_EXTENSIONS].join(',');
  button.title = `Open a height field (${ACCEPTED}), images to drape on it (${DRAPED_FORMATS}, with their world files), or both; ` +
    'a .prj or GDAL .aux.xml gives the CRS of the file it is named after';
  button.onclick = () => picker.click();
  picker.onchange = () => {
    if (picker.files.length) openPicked(picker.files); // takes the list at once: it is emptied next
    picker.value = '';
  };
}
