// The height profile as a chart on a 2D canvas: height against distance along the line, with
// axes in metres or kilometres, the area under the curve shaded, breaks where the line left the
// field, and a cursor that follows the pointer (the page marks the same point on the terrain).
// A track's profile also carries the elevations its file recorded (GPS): a second curve.

const FONT = '11px system-ui, sans-serif';
const COLORS = { axis: '#9aa6b8', grid: 'rgba(232, 238, 246, 0.12)', text: '#d8e0ea', line: '#ffd22e',
  fill: 'rgba(255, 210, 46, 0.18)', cursor: '#33d9ff', background: '#141a24', recorded: '#ff5fa8' };
const MARGIN = { left: 30, right: 10, top: 8, bottom: 22 };

/** Round tick steps (1, 2, 2.5, 5 times a power of ten) giving about `count` ticks over [lo, hi]. */
export function niceTicks(lo, hi, count) {
  const span = hi - lo;
  if (!(span > 0)) return { step: 1, ticks: [lo] };
  const raw = span / Math.max(1, count), power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * power).find((s) => s >= raw) ?? 10 * power;
  const ticks = [];
  for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) ticks.push(Number(t.toPrecision(12)));
  return { step, ticks };
}

/** Distance axis in km from 5 km on, else m. */
const distanceUnit = (length) => (length >= 5000 ? { unit: 'km', scale: 1000 } : { unit: 'm', scale: 1 });

export class ProfileChart {
  /**
   * @param {HTMLCanvasElement} canvas sized by CSS; drawn at the device's pixel ratio
   * @param {{onHover: (index: number|null) => void}} handlers the sample under the pointer, or null
   */
  constructor(canvas, { onHover }) {
    this.canvas = canvas;
    this.onHover = onHover;
    this.profile = null;
    this.hover = null; // sample index
    canvas.addEventListener('pointermove', (e) => this.pointAt(e));
    canvas.addEventListener('pointerdown', (e) => this.pointAt(e));
    canvas.addEventListener('pointerleave', (e) => { if (e.pointerType !== 'touch') this.setHover(null); });
  }

  /** Shows a profile (web/measure/profile.js), or nothing for null. */
  show(profile) {
    const hovered = this.hover !== null;
    this.profile = profile;
    this.hover = null;
    this.draw();
    if (hovered) this.onHover(null); // the old line's point is no longer marked
  }

  /** The sample nearest the pointer's distance along the line. */
  pointAt(e) {
    const p = this.profile;
    if (!p || !this.frame) return;
    const rect = this.canvas.getBoundingClientRect();
    const d = this.frame.toDistance(e.clientX - rect.left);
    const distance = p.samples.distance;
    // Distances grow along the samples: bisect.
    let lo = 0, hi = distance.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (distance[mid] < d) lo = mid; else hi = mid;
    }
    this.setHover(Math.abs(distance[lo] - d) <= Math.abs(distance[hi] - d) ? lo : hi);
  }

  setHover(index) {
    if (index === this.hover) return;
    this.hover = index;
    this.draw();
    this.onHover(index);
  }

  draw() {
    const canvas = this.canvas, dpr = window.devicePixelRatio || 1;
    const cssWidth = Math.max(1, canvas.clientWidth), cssHeight = Math.max(1, canvas.clientHeight);
    if (canvas.width !== Math.round(cssWidth * dpr) || canvas.height !== Math.round(cssHeight * dpr)) {
      canvas.width = Math.round(cssWidth * dpr);
      canvas.height = Math.round(cssHeight * dpr);
    }
    const g = canvas.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.fillStyle = COLORS.background;
    g.fillRect(0, 0, cssWidth, cssHeight);
    this.frame = null;
    const p = this.profile;
    if (!p) return;
    const { distance, height, runStart } = p.samples, recorded = p.samples.gpsElevation ?? null;
    const n = distance.length;
    let low = Infinity, high = -Infinity;
    for (let k = 0; k < n; k++) if (Number.isFinite(height[k])) low = Math.min(low, height[k]), high = Math.max(high, height[k]);
    for (let k = 0; recorded && k < n; k++) if (Number.isFinite(recorded[k])) low = Math.min(low, recorded[k]), high = Math.max(high, recorded[k]);
    if (!(high >= low)) return;
    // The height axis runs from a tick below the lowest point to one above the highest.
    const pad = Math.max((high - low) * 0.05, 1);
    const { step } = niceTicks(low - pad, high + pad, Math.max(2, Math.floor((cssHeight - MARGIN.top - MARGIN.bottom) / 18)));
    const y0 = Math.floor((low - pad) / step) * step, y1 = Math.ceil((high + pad) / step) * step;
    const yTicks = niceTicks(y0, y1, Math.round((y1 - y0) / step));
    const dMax = distance[n - 1] || 1;
    const { unit, scale } = distanceUnit(dMax);
    const xTicks = niceTicks(0, dMax / scale, Math.max(2, Math.floor(cssWidth / 80)));
    g.font = FONT;
    // The left margin fits the widest height label.
    const yLabels = yTicks.ticks.map((t) => `${t.toLocaleString('en')} m`);
    const left = Math.max(MARGIN.left, Math.ceil(Math.max(...yLabels.map((l) => g.measureText(l).width))) + 8), right = cssWidth - MARGIN.right, top = MARGIN.top, bottom = cssHeight - MARGIN.bottom;
    const sx = (d) => left + (d / dMax) * (right - left);
    const sy = (h) => bottom - ((h - y0) / (y1 - y0 || 1)) * (bottom - top);
    this.frame = { toDistance: (px) => Math.min(Math.max(((px - left) / (right - left)) * dMax, 0), dMax) };

    g.font = FONT;
    g.lineWidth = 1;
    // Grid and tick labels.
    g.fillStyle = COLORS.text;
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    // A label at most every 16 px: on a short chart every other grid line goes unlabelled.
    const labelEvery = Math.ceil(16 / Math.max(1e-6, (bottom - top) / Math.max(1, yTicks.ticks.length - 1)));
    yTicks.ticks.forEach((t, i) => {
      if (t < y0 || t > y1) return;
      const y = Math.round(sy(t)) + 0.5;
      g.strokeStyle = COLORS.grid;
      g.beginPath(); g.moveTo(left, y); g.lineTo(right, y); g.stroke();
      if (i % labelEvery === 0) g.fillText(yLabels[i], left - 4, y);
    });
    g.textAlign = 'center';
    g.textBaseline = 'top';
    for (const t of xTicks.ticks) {
      const x = Math.round(sx(t * scale)) + 0.5;
      if (x > right + 1) continue;
      g.strokeStyle = COLORS.grid;
      g.beginPath(); g.moveTo(x, top); g.lineTo(x, bottom); g.stroke();
      const label = `${t.toLocaleString('en')}${t === 0 ? '' : ` ${unit}`}`;
      g.fillText(label, Math.min(Math.max(x, left + 8), right - 14), bottom + 5);
    }
    // Axes.
    g.strokeStyle = COLORS.axis;
    g.beginPath(); g.moveTo(left + 0.5, top); g.lineTo(left + 0.5, bottom + 0.5); g.lineTo(right, bottom + 0.5); g.stroke();
    // Filled area and curve, one run at a time (a run ends where the line left the field); a
    // long profile (a track of half a million points) is drawn from each pixel column's first,
    // lowest, highest and last samples, which is all a column can show.
    const runs = [], columnOf = (k) => Math.floor(sx(distance[k]));
    let column = NaN, first = -1, lowest = -1, highest = -1, last = -1;
    const flush = () => {
      if (first < 0) return;
      const run = runs[runs.length - 1];
      for (const k of [...new Set([first, lowest, highest, last])].sort((a, b) => a - b)) run.push(k);
      first = -1;
    };
    for (let k = 0; k < n; k++) {
      const breaks = k === 0 || runStart[k] === 1 || !Number.isFinite(height[k]);
      if (breaks || columnOf(k) !== column) flush();
      if (breaks) runs.push([]);
      if (!Number.isFinite(height[k])) continue;
      if (first < 0) { first = lowest = highest = k; column = columnOf(k); }
      if (height[k] < height[lowest]) lowest = k;
      if (height[k] > height[highest]) highest = k;
      last = k;
    }
    flush();
    for (const run of runs) {
      if (run.length === 0) continue;
      g.beginPath();
      g.moveTo(sx(distance[run[0]]), bottom);
      for (const k of run) g.lineTo(sx(distance[k]), sy(height[k]));
      g.lineTo(sx(distance[run[run.length - 1]]), bottom);
      g.closePath();
      g.fillStyle = COLORS.fill;
      g.fill();
      g.beginPath();
      run.forEach((k, i) => (i === 0 ? g.moveTo(sx(distance[k]), sy(height[k])) : g.lineTo(sx(distance[k]), sy(height[k]))));
      g.strokeStyle = COLORS.line;
      g.lineWidth = 1.8;
      g.stroke();
      g.lineWidth = 1;
    }
    if (recorded) this.drawRecorded(g, recorded, runs, distance, sx, sy, right, top);
    // The hovered sample.
    if (this.hover !== null && Number.isFinite(height[this.hover])) {
      const x = sx(distance[this.hover]), y = sy(height[this.hover]);
      g.strokeStyle = COLORS.cursor;
      g.beginPath(); g.moveTo(x, top); g.lineTo(x, bottom); g.stroke();
      g.fillStyle = COLORS.cursor;
      g.beginPath(); g.arc(x, y, 3.5, 0, 2 * Math.PI); g.fill();
    }
  }

  /** The file's own elevations along a track, where it has them (at the samples drawn), and the two curves' names. */
  drawRecorded(g, recorded, runs, distance, sx, sy, right, top) {
    g.beginPath();
    for (const run of runs) {
      let drawing = false;
      for (const k of run) {
        if (!Number.isFinite(recorded[k])) { drawing = false; continue; }
        if (drawing) g.lineTo(sx(distance[k]), sy(recorded[k]));
        else g.moveTo(sx(distance[k]), sy(recorded[k]));
        drawing = true;
      }
    }
    g.strokeStyle = COLORS.recorded;
    g.lineWidth = 1.4;
    g.stroke();
    g.lineWidth = 1;
    g.textAlign = 'right';
    g.textBaseline = 'top';
    g.fillStyle = COLORS.recorded;
    g.fillText('recorded', right - 4, top + 2);
    g.fillStyle = COLORS.line;
    g.fillText('terrain', right - 4 - g.measureText('recorded ').width - 4, top + 2);
  }
}
