// The file bar's spacing field: the terrain's metres between samples, east-west (and north-south
// beside it when the cells are not square), outlined while it is a guess. Applying it sets the
// panel's cell size setting: the terrain is scaled in place, the cameras with it.

/** Metres as the field shows them: six significant digits, no trailing zeros. */
const formatMetres = (metres) => String(Number(metres.toPrecision(6)));

/**
 * @param {{ state: object, layers: import('../app/layers.js').Layers, showStatus: (message: string, isError?: boolean) => void,
 *   setCellSize: (metres: number) => boolean }} page
 *   setCellSize: the panel's cell size setting (east-west metres; north-south keeps its ratio),
 *   false when refused (the page shows why)
 * @returns {(terrain: object, assumed?: boolean) => void} shows a terrain's spacing; `assumed`:
 *   a guess (the file said nothing), outlined until the user sets one here or in the panel
 */
export function installSpacingField({ dom, state, layers, showStatus, setCellSize }) {
  const $ = (id) => dom.byId(id);
  const input = $('spacing-input'), form = $('spacing-form'), ratio = $('spacing-ratio');

  function showSpacing(terrain, assumed = false) {
    form.classList.toggle('assumed', assumed);
    input.value = formatMetres(terrain.spacingX);
    const square = Math.abs(terrain.spacingY - terrain.spacingX) <= 1e-9 * terrain.spacingX;
    ratio.hidden = square;
    ratio.textContent = square ? '' : `(${formatMetres(terrain.spacingY)} m north–south)`;
    input.title = square ? 'metres between samples' : 'metres between columns (east–west); rows scale with them';
  }

  // The form is novalidate: our message, not the browser's bubble, says what is wrong. A bad
  // value leaves the terrain as it is, and the page says why.
  form.onsubmit = (e) => {
    e.preventDefault();
    if (state.loading || !layers.ground) return;
    // '' also for text that is not a number, which Number() would read as 0.
    const text = input.value.trim();
    if (text === '') showStatus('spacing: type the metres between samples, a positive number', true);
    else if (setCellSize(Number(text))) return; // the setting's effect shows the new spacing
    input.value = formatMetres(layers.ground.terrain.spacingX); // what is in effect again
  };
  return showSpacing;
}
