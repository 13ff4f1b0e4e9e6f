// The measuring panel (public/index.html #measure): path or area, the profile chart, the
// summary figures in metres or kilometres, what the chart's cursor points at, notes (a line
// partly off the field), and the buttons: undo, done, clear, CSV and PNG export. It folds to its
// title bar, so on a phone it never covers the whole view.
import { ProfileChart } from './profile_chart.js';
import { profileCsv } from '../measure/profile_csv.js';
import { formatLength } from '../measure/units.js';
import { geoCoordinates, formatCoordinates } from '../geo/index.js';

const HINT = {
  path: 'Click points on the ground (or Space: the view\'s centre) · double click or Enter ends · Backspace undoes · Esc clears',
  area: 'Click the corners (or Space: the view\'s centre) · double click or Enter closes · Backspace undoes · Esc clears',
  track: 'A track of an overlay · click another line for its profile, or the ground for a path of your own · Esc clears',
};

/** '850 m²', '12.4 ha', '3.52 km²': hectares between a hectare and a square kilometre. */
export function formatAreaUnits(squareMetres) {
  const a = Math.abs(squareMetres);
  if (a < 1e4) return `${Number(squareMetres.toPrecision(3)).toLocaleString('en')} m²`;
  if (a < 1e6) return `${Number((squareMetres / 1e4).toPrecision(3))} ha`;
  return `${(squareMetres / 1e6).toLocaleString('en', { maximumFractionDigits: a < 1e8 ? 2 : 0 })} km²`;
}

const heightText = (m) => `${Math.round(m).toLocaleString('en')} m`;

/** '1 h 05 min', '12 min 30 s', '45 s'. */
export function formatDuration(seconds) {
  const s = Math.round(seconds), h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  if (h > 0) return `${h} h ${String(m).padStart(2, '0')} min`;
  return m > 0 ? `${m} min ${String(r).padStart(2, '0')} s` : `${r} s`;
}

const speedText = (metresPerSecond) => `${(metresPerSecond * 3.6).toFixed(1)} km/h`;

/** A track's own figures: what its file recorded (elevations, times). */
function trackRows(s) {
  const rows = [];
  if (Number.isFinite(s.gpsGain)) rows.push(['recorded gain', heightText(s.gpsGain)], ['recorded loss', heightText(s.gpsLoss)]);
  if (s.duration !== null && s.duration !== undefined) rows.push(['time', formatDuration(s.duration)]);
  if (s.averageSpeed !== null && s.averageSpeed !== undefined) rows.push(['mean speed', speedText(s.averageSpeed)]);
  if (s.movingSpeed !== null && s.movingSpeed !== undefined) rows.push(['moving speed', speedText(s.movingSpeed)]);
  return rows;
}
const degrees = (d) => `${d.toFixed(1)}°`;

export class MeasurePanel {
  /**
   * @param {{setKind(kind): void, undo(): void, finish(): void, clear(): void, setActive(on): void,
   *   onHover(point: number[]|null): void, download(blob: Blob, name: string): void, name: () => string}} actions
   * @param {import('../app/viewer_dom.js').ViewerDom} dom  the viewer's elements
   */
  constructor(actions, dom) {
    this.actions = actions;
    this.$ = (id) => dom.byId(id);
    const $ = this.$;
    this.root = $('measure');
    this.result = null;
    this.chart = new ProfileChart($('profile-chart'), { onHover: (index) => this.hovered(index) });
    $('measure-path').onclick = () => actions.setKind('path');
    $('measure-area').onclick = () => actions.setKind('area');
    $('measure-undo').onclick = () => actions.undo();
    $('measure-done').onclick = () => actions.finish();
    $('measure-clear').onclick = () => actions.clear();
    $('measure-close').onclick = () => actions.setActive(false);
    $('measure-fold').onclick = () => this.setFolded(!this.root.classList.contains('folded'));
    $('measure-csv').onclick = () => this.exportCsv();
    $('measure-png').onclick = () => this.exportPng();
    dom.onResize(() => { if (!this.root.hidden) this.chart.draw(); });
  }

  setFolded(folded) {
    this.root.classList.toggle('folded', folded);
    this.$('measure-fold').textContent = folded ? '▸' : '▾';
    this.$('measure-fold').setAttribute('aria-expanded', String(!folded));
    if (!folded) this.chart.draw();
  }

  /** A new measurement (measure_tool.js update()). */
  show(result) {
    this.result = result;
    this.root.hidden = !result.active;
    if (!result.active) return;
    const area = result.kind === 'area';
    this.$('measure-title').textContent = area ? 'Area' : result.track ? `Track: ${result.track}` : 'Profile';
    this.$('measure-path').setAttribute('aria-pressed', String(!area));
    this.$('measure-area').setAttribute('aria-pressed', String(area));
    this.$('measure-hint').textContent = result.track ? HINT.track : result.finished ? (area ? 'Area closed · click to start another' : 'Path finished · click to start another') : HINT[result.kind];
    const notes = [result.error, result.profile?.clipped && `Clipped: ${result.profile.clipped}.`, result.area?.note, result.profile?.note].filter(Boolean);
    this.$('measure-note').textContent = notes.join(' ');
    this.$('measure-note').hidden = notes.length === 0;
    // Each figure a <div> of its label over its value (a <dl> may group them so).
    this.$('measure-summary').replaceChildren(...this.summaryRows(result).map(([label, value]) => {
      const item = document.createElement('div'), dt = document.createElement('dt'), dd = document.createElement('dd');
      dt.textContent = label;
      dd.textContent = value;
      item.append(dt, dd);
      return item;
    }));
    this.$('measure-hover').textContent = '';
    this.root.classList.toggle('empty', result.profile === null);
    const canExport = result.profile !== null;
    this.$('measure-csv').disabled = this.$('measure-png').disabled = !canExport;
    this.$('measure-undo').disabled = result.points.length === 0;
    this.$('measure-done').disabled = result.finished || result.points.length < (area ? 3 : 2);
    this.$('measure-clear').disabled = result.points.length === 0 && !result.track;
    this.chart.show(result.profile);
  }

  /** [label, value] pairs of the summary (the same figures the test reads). */
  summaryRows(result) {
    const rows = [];
    const a = result.area, s = result.profile?.summary;
    if (result.kind === 'area' && a) {
      rows.push(['area (map)', formatAreaUnits(a.planimetric)], ['surface area', formatAreaUnits(a.surface)],
        ['perimeter', formatLength(a.perimeter)], ['perimeter 3D', formatLength(a.perimeter3d)]);
    }
    if (s) {
      if (result.kind !== 'area') rows.push(['length', formatLength(s.length)], ['3D length', formatLength(s.length3d)]);
      rows.push(['gain', heightText(s.gain)], ['loss', heightText(s.loss)], ['min', heightText(s.min)], ['max', heightText(s.max)],
        ['mean slope', degrees(s.meanSlope)], ['steepest', degrees(s.steepestSlope)]);
      if (result.track) rows.push(...trackRows(s));
    }
    if (!rows.length) rows.push(['points', String(result.points.length)]);
    return rows;
  }

  /** The chart's cursor moved to sample `index` (or left it). */
  hovered(index) {
    const p = this.result?.profile;
    if (index === null || !p || !Number.isFinite(p.samples.height[index])) {
      this.$('measure-hover').textContent = '';
      this.actions.onHover(null);
      return;
    }
    const { distance, x, z, height } = p.samples;
    const spacingX = p.spacingX, spacingY = p.spacingY;
    // Where it is: real coordinates when the field has them, else local metres.
    const place = this.result.georef ? formatCoordinates(geoCoordinates(this.result.georef, x[index], z[index], spacingX, spacingY))
      : `x ${formatLength(x[index])}, z ${formatLength(z[index])}`;
    const recorded = p.samples.gpsElevation?.[index];
    const own = Number.isFinite(recorded) ? ` (recorded ${heightText(recorded)})` : '';
    this.$('measure-hover').textContent = `at ${formatLength(distance[index])}: height ${heightText(height[index])}${own} · ${place}`;
    this.actions.onHover([x[index], height[index], z[index]]);
  }

  exportCsv() {
    const p = this.result?.profile;
    if (!p) return;
    const text = profileCsv(p, this.result.georef);
    const what = this.result.kind === 'area' ? 'outline' : this.result.track ? `${this.result.track.replace(/\.[^.]*$/, '')}-profile` : 'profile';
    this.actions.download(new Blob([text], { type: 'text/csv' }), `${this.actions.name()}-${what}.csv`);
  }

  exportPng() {
    if (!this.result?.profile) return;
    this.$('profile-chart').toBlob((blob) => blob && this.actions.download(blob, `${this.actions.name()}-profile.png`), 'image/png');
  }
}
