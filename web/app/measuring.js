// Wires the measuring tool (web/ui/measure_tool.js) to the page: its line drawn by the
// renderer's overlay, its results in the panel (web/ui/measure_panel.js), its value in the
// address bar, its exports through the page's download, and (test mode) window.hexlod.measure.
import { MeasureTool } from '../ui/measure_tool.js';
import { MeasurePanel } from '../ui/measure_panel.js';
import { download } from './screenshot.js';

/**
 * @param {object} parts canvas, rig, settings, stage (web/app/terrain_stage.js), renderer,
 *   urlWriter, requestRender(), state (window.hexlod in test mode)
 * @returns {MeasureTool}
 */
export function installMeasuring({ dom, canvas, rig, settings, stage, renderer, urlWriter, requestRender, state }) {
  const overlay = renderer.measureOverlay;
  let tool = null;
  const button = dom.byId('measure-button'); // in the file bar: on, off
  const panel = new MeasurePanel({
    setKind: (kind) => tool.setKind(kind), undo: () => tool.undo(), finish: () => tool.finish(), clear: () => tool.clear(),
    setActive: (on) => tool.setActive(on), download,
    onHover: (point) => { overlay.setHover(point); requestRender(); },
    name: () => `hexlod-${(stage.current?.field.source ?? 'view').replace(/\.[^.]*$/, '')}`,
  }, dom);
  tool = new MeasureTool({ dom, canvas, rig, settings, overlay, requestRender,
    terrain: () => stage.current,
    onResult: (result) => {
      panel.show(result);
      button.setAttribute('aria-pressed', String(result.active));
    },
    onParam: (text) => { urlWriter.measure = text; } });
  tool.attach();
  button.onclick = () => tool.toggle();
  // Not enumerable: the tool holds the terrain, which a test's evaluate(() => window.hexlod) would copy.
  Object.defineProperty(state, 'measure', { value: tool, enumerable: false, configurable: true });
  Object.defineProperty(state, 'measurePanel', { value: panel, enumerable: false, configurable: true });
  return tool;
}
