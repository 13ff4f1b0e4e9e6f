// Where files come in by hand: dropped anywhere on the page, or chosen with the Open button's
// file picker. Both hand the files to one opener as one load.
import { ACCEPT_EXTENSIONS, ACCEPTED } from '../loaders/index.js';
import { IMAGE_EXTENSIONS } from '../imagery/drop_roles.js';
import { DRAPED_FORMATS } from '../imagery/image_formats.js';

/** @param {(files: FileList) => Promise<string>} openPicked */
export function installDropTarget(openPicked) {
  const picker = document.getElementById('file-input'), button = document.getElementById('open-button');
  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', async (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    const dropped = e.dataTransfer?.files ?? [];
    if (dropped.length) await openPicked(dropped);
  });
  picker.accept = [...ACCEPT_EXTENSIONS, ...IMAGE_EXTENSIONS].join(',');
  button.title = `Open a height field (${ACCEPTED}), an image to drape on it (${DRAPED_FORMATS}, with its world file), or both`;
  button.onclick = () => picker.click();
  picker.onchange = () => {
    if (picker.files.length) openPicked(picker.files); // takes the list at once: it is emptied next
    picker.value = '';
  };
}
