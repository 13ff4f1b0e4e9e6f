// The dialog that asks the width and height of a RAW file that does not say them.

/**
 * Asks the size of `name`, a RAW file of `samples` 16-bit samples.
 * @returns {Promise<{width: number, height: number}|null>} null when cancelled (or the load is)
 */
export function askRawSize(dom, name, samples, signal) {
  const $ = (id) => dom.byId(id);
  const dialog = $('raw-dialog'), form = $('raw-form'), width = $('raw-width'), height = $('raw-height');
  $('raw-name').textContent = `${name} holds ${samples.toLocaleString('en')} 16-bit samples.`;
  width.value = '';
  height.value = '';
  width.oninput = () => { if (samples % Number(width.value) === 0) height.value = samples / Number(width.value); };
  return new Promise((resolve) => {
    const answer = (size) => {
      signal.removeEventListener('abort', onAbort);
      dialog.close();
      resolve(size);
    };
    const onAbort = () => answer(null);
    form.onsubmit = (e) => {
      e.preventDefault();
      answer({ width: Number(width.value), height: Number(height.value) });
    };
    $('raw-cancel').onclick = () => answer(null);
    signal.addEventListener('abort', onAbort);
    dialog.showModal();
  });
}
