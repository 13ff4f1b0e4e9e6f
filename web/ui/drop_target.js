// Where files come in by hand: dropped anywhere on the page (files, or a folder as its files),
// or chosen with the Open button's file picker. Both hand the files to one opener as one load.
import { ACCEPT_EXTENSIONS, ACCEPTED } from '../loaders/index.js';
import { IMAGE_EXTENSIONS } from '../imagery/drop_roles.js';
import { OVERLAY_EXTENSIONS } from '../overlays/overlay_kind.js';
import { DRAPED_FORMATS } from '../imagery/image_formats.js';
import { droppedFiles, MAX_DROPPED_FILES } from './dropped_files.js';

/**
 * @param {import('../app/viewer_dom.js').ViewerDom} dom  the viewer: its file picker, and where drops land
 * @param {(files: FileList|File[]) => Promise<string>} openPicked
 * @param {(message: string, isError?: boolean) => void} showStatus
 * @param {boolean} [drops] whether files dropped onto the viewer open (a bare canvas takes none)
 */
export function installDropTarget(dom, openPicked, showStatus, drops = true) {
  const picker = dom.byId('file-input'), button = dom.byId('open-button');
  if (drops) installDrops(dom, openPicked, showStatus);
  picker.accept = [...ACCEPT_EXTENSIONS, ...IMAGE_EXTENSIONS, ...OVERLAY_EXTENSIONS].join(',');
  button.title = `Open a height field (${ACCEPTED}), images to drape on it (${DRAPED_FORMATS}, with their world files), or both; ` +
    'a .prj or GDAL .aux.xml gives the CRS of the file it is named after';
  button.onclick = () => picker.click();
  picker.onchange = () => {
    if (picker.files.length) openPicked(picker.files); // takes the list at once: it is emptied next
    picker.value = '';
  };
}

/** Files or a folder dropped onto the viewer (the page: anywhere on it) open as one load. */
function installDrops(dom, openPicked, showStatus) {
  const dragging = (on) => dom.root.classList.toggle('dragging', on);
  dom.on(dom.dropTarget, 'dragover', (e) => {
    e.preventDefault();
    dragging(true);
  });
  dom.on(dom.dropTarget, 'dragleave', () => dragging(false));
  dom.on(dom.dropTarget, 'drop', async (e) => {
    e.preventDefault();
    dragging(false);
    const { files, truncated } = await droppedFiles(e.dataTransfer);
    if (truncated) {
      showStatus(`the dropped folder holds more than ${MAX_DROPPED_FILES} files: drop the files of one terrain`, true);
      return;
    }
    if (files.length) await openPicked(files);
  });
}
