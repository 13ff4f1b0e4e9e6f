// The files of a drop: the files themselves, and a dropped folder as the files inside it (and
// inside its folders), read through the entries API (DataTransferItem.webkitGetAsEntry).
// The entries must be taken while the drop event is handled; they are read afterwards.

/** Past this a folder's files are not read further (a whole disk dropped by mistake). */
export const MAX_DROPPED_FILES = 2000;

/**
 * Takes the drop's files and folders now, during the event, and reads the folders' files.
 * @param {DataTransfer|null} transfer
 * @returns {Promise<{ files: File[], truncated: boolean }>} a folder's files sorted by path;
 *   truncated when a folder held more than MAX_DROPPED_FILES
 */
export function droppedFiles(transfer) {
  const files = [...(transfer?.files ?? [])];
  const entries = [...(transfer?.items ?? [])].filter((item) => item.kind === 'file').map((item) => item.webkitGetAsEntry?.() ?? null);
  // Without the entries API, or without a folder: the files as the drop gives them.
  if (entries.length === 0 || entries.some((entry) => entry === null) || !entries.some((entry) => entry.isDirectory)) {
    return Promise.resolve({ files, truncated: false });
  }
  return readEntries(entries);
}

/** The files under entries, depth first; hidden files (.DS_Store) are left out. */
async function readEntries(entries) {
  const files = [];
  let truncated = false;
  const visit = async (entry) => {
    if (files.length >= MAX_DROPPED_FILES) {
      truncated = true;
      return;
    }
    if (entry.isFile) {
      if (!entry.name.startsWith('.')) files.push(await new Promise((resolve, reject) => entry.file(resolve, reject)));
    } else if (entry.isDirectory) {
      const children = await folderEntries(entry);
      children.sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0)); // the browser's order is its own
      for (const child of children) await visit(child);
    }
  };
  for (const entry of entries) await visit(entry);
  return { files, truncated };
}

/** All entries of a folder: its reader gives them in batches until an empty one. */
async function folderEntries(folder) {
  const reader = folder.createReader(), all = [];
  for (;;) {
    const batch = await new Promise((resolve, reject) => reader.readEntries(resolve, reject));
    if (batch.length === 0) return all;
    all.push(...batch);
  }
}
