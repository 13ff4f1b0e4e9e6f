// The viewer's elements, one copy per viewer: the canvas, the status line and HUD, the file bar,
// the measuring panel, the help box and the RAW size dialog. The page (public/index.html) and
// createViewer() (web/api/) both put this markup into their container; every part then finds its
// elements through the viewer's own ViewerDom (viewer_dom.js), never through the document, so two
// viewers on one page each find their own.

/** The markup inside one viewer's root element (class "hexlod"). */
export const VIEWER_MARKUP = `
  <canvas id="view" aria-label="terrain view"></canvas>
  <!-- The status line stacks above the HUD in one column, so a long message never hides a figure. -->
  <div id="bottom-bar">
    <!-- The measuring tool's results (web/ui/measure_panel.js): shown while the tool is on. -->
    <section id="measure" hidden aria-label="measurement">
      <header><strong id="measure-title">Profile</strong>
        <span class="measure-kinds"><button id="measure-path" type="button" aria-pressed="true">Path</button><button id="measure-area" type="button" aria-pressed="false">Area</button></span>
        <button id="measure-fold" type="button" title="fold or unfold" aria-expanded="true">▾</button>
        <button id="measure-close" type="button" title="end measuring (M)">✕</button></header>
      <div class="measure-body">
        <p id="measure-hint"></p>
        <p id="measure-note" hidden></p>
        <canvas id="profile-chart" aria-label="height profile"></canvas>
        <p id="measure-hover"></p>
        <dl id="measure-summary"></dl>
        <div class="measure-actions"><button id="measure-undo" type="button">Undo</button><button id="measure-done" type="button">Done</button><button id="measure-clear" type="button">Clear</button>
          <button id="measure-csv" type="button" title="the profile's samples as CSV">CSV</button><button id="measure-png" type="button" title="the chart as PNG">PNG</button></div>
      </div>
    </section>
    <div id="status" role="status">Loading…</div>
    <div id="hud" aria-live="polite"></div>
  </div>
  <div id="drop-hint">Drop a height field, an image or a GPX, KML or GeoJSON file anywhere · H: help</div>
  <div id="attribution" hidden></div>
  <!-- The overlay feature under the pointer: its name and properties (web/app/overlay_pointer.js). -->
  <div id="overlay-tip" role="tooltip" hidden></div>
  <div id="side">
    <div id="intake">
      <button id="open-button" type="button">Open file…</button>
      <button id="measure-button" type="button" aria-pressed="false" title="measure a profile or an area (M)">Measure</button>
      <input id="file-input" type="file" multiple hidden>
      <label>PNG colours <select id="png-encoding">
        <option value="auto">auto</option><option value="terrain-rgb">Terrain-RGB</option><option value="terrarium">Terrarium</option><option value="image">image (drape)</option>
      </select></label>
      <form id="spacing-form" novalidate><label>spacing <input id="spacing-input" type="number" min="0" step="any" size="6"> m</label>
        <span id="spacing-ratio" hidden></span>
        <button type="submit">Apply</button></form>
      <progress id="load-progress" max="1" value="0" hidden></progress>
      <button id="load-cancel" type="button" hidden title="stop this load; the terrain on screen stays">Cancel</button>
    </div>
    <div id="panel"></div>
  </div>
  <section id="help" hidden aria-label="keyboard and mouse shortcuts">
    <h2>Shortcuts</h2>
    <table>
      <tr><th>1 2 3</th><td>orbit, fly, walk camera</td></tr>
      <tr><th>drag</th><td>orbit (orbit camera), look around (fly, walk)</td></tr>
      <tr><th>right drag, shift drag</th><td>pan (orbit camera)</td></tr>
      <tr><th>wheel</th><td>zoom (orbit), move ahead (fly, walk)</td></tr>
      <tr><th>double click</th><td>orbit around the point under the pointer</td></tr>
      <tr><th>W A S D, arrows</th><td>move (fly, walk); speed follows the height above the ground</td></tr>
      <tr><th>Q E, PgDn PgUp</th><td>down, up (fly)</td></tr>
      <tr><th>shift</th><td>fast</td></tr>
      <tr><th>touch</th><td>one finger orbits, pinch zooms, two fingers pan</td></tr>
      <tr><th>M</th><td>measure: click points on the terrain for a profile or an area; double click or Enter ends, Backspace undoes, Esc clears</td></tr>
      <tr><th>L</th><td>colour by level</td></tr>
      <tr><th>O</th><td>wireframe: hexagon outlines</td></tr>
      <tr><th>F</th><td>freeze LOD: keep the mesh while the camera moves</td></tr>
      <tr><th>P</th><td>screenshot (PNG; 2× in the panel)</td></tr>
      <tr><th>R</th><td>reset the view</td></tr>
      <tr><th>I</th><td>fold or unfold the figures (HUD)</td></tr>
      <tr><th>H, ?</th><td>this help</td></tr>
    </table>
    <p>Drop a height field anywhere on the page, or use "Open file…": PNG (grayscale, Terrain-RGB, Terrarium),
      GeoTIFF, SRTM .hgt, .asc, .pgm, .r16/.raw, or .f32 with its .json; a NAME.json beside it may give the cell size.</p>
    <p>The address bar holds the view (camera, τ, budget, exaggeration, data URL): copy it to share.</p>
    <button id="help-close" type="button">Close</button>
  </section>
  <dialog id="raw-dialog">
    <form id="raw-form" method="dialog">
      <p id="raw-name"></p>
      <label>width <input id="raw-width" type="number" min="1" required></label>
      <label>height <input id="raw-height" type="number" min="1" required></label>
      <button type="submit">Load</button> <button id="raw-cancel" type="button">Cancel</button>
    </form>
  </dialog>
`;
