// The measuring tool: a mode the user turns on (M or the panel), then clicks points on the
// terrain to draw a path (its height profile and length) or a closed polygon (its area). A click
// or tap that does not move adds a point, so the cameras' drags keep working in every camera;
// double click, a double tap, Enter or Done finishes; Backspace or Undo takes the last point
// back; Escape or Clear starts over. The line lives in local metres (x east, z south) and in the
// address bar as `measure=p:x,z;x,z;...` (a path) or `measure=a:...` (an area).
import { pickGround } from '../cameras/picking.js';
import { isTyping } from '../cameras/rig.js';
import { fieldSampler } from '../measure/field_sampler.js';
import { computeProfile } from '../measure/profile.js';
import { measurePolygon } from '../measure/polygon_area.js';

const CLICK_PX = 6;       // a press that moves farther is a drag (the camera's), not a click
const TAP_MS = 600;       // a longer touch is a hold, not a tap
const DOUBLE_MS = 450;    // the second press of a double click or tap
const MAX_URL_POINTS = 200;

/** The `measure` URL value of a line: kind letter, then x,z pairs rounded to a tenth of the spacing. */
export function measureParam(kind, points, spacing) {
  const digits = Math.max(0, Math.min(3, Math.ceil(-Math.log10(spacing / 10))));
  const pairs = points.map(([x, z]) => `${Number(x.toFixed(digits))},${Number(z.toFixed(digits))}`);
  return `${kind === 'area' ? 'a' : 'p'}:${pairs.join(';')}`;
}

/**
 * Reads a `measure` URL value: {kind, points} or an Error saying what is wrong.
 * @param {string} text
 */
export function parseMeasureParam(text) {
  const bad = (why) => new Error(`measure=${text.length > 60 ? `${text.slice(0, 60)}…` : text}: ${why}; expected p:x,z;x,z;... or a:x,z;x,z;x,z;... (metres)`);
  const m = /^([pa]):(.*)$/.exec(text.trim());
  if (!m) return bad('it must start with p: (a path) or a: (an area)');
  const kind = m[1] === 'a' ? 'area' : 'path';
  const pairs = m[2].split(';').filter((s) => s.trim() !== '');
  if (pairs.length > MAX_URL_POINTS) return bad(`at most ${MAX_URL_POINTS} points`);
  const points = [];
  for (const pair of pairs) {
    const values = pair.split(',');
    const [x, z] = values.map(Number);
    if (values.length !== 2 || values.some((v) => v.trim() === '') || !Number.isFinite(x) || !Number.isFinite(z) || Math.abs(x) > 1e9 || Math.abs(z) > 1e9) {
      return bad(`'${pair}' is not an x,z pair of numbers`);
    }
    points.push([x, z]);
  }
  const needed = kind === 'area' ? 3 : 2;
  if (points.length < needed) return bad(`${kind === 'area' ? 'an area' : 'a path'} needs at least ${needed} points`);
  return { kind, points };
}

export class MeasureTool {
  /**
   * @param {object} parts canvas, rig, settings, terrain() (the loaded terrain: { terrain, field,
   *   world } or null), overlay (web/render/measure_overlay.js), onResult(result) (the panel),
   *   onParam(text|null) (the address bar), requestRender()
   */
  constructor(parts) {
    Object.assign(this, parts);
    this.active = false;
    this.kind = 'path';
    this.points = [];
    this.finished = false;
    this.result = null;
    this.lastClick = null; // {x, y, time} of the last press that added a point
    this.track = null;     // an overlay's track shown instead of clicked points: { name, profile }
    this.lineAt = null;    // (clientX, clientY) => whether an overlay's line there took the click (app/overlay_pointer.js)
  }

  /** Turns the mode on or off; off clears the line. */
  setActive(on) {
    if (on === this.active) return;
    this.active = on;
    if (!on) this.clear();
    else this.update();
  }

  toggle() { this.setActive(!this.active); }

  /** 'path' or 'area': the same points, measured the other way. */
  setKind(kind) {
    this.track = null;
    this.kind = kind === 'area' ? 'area' : 'path';
    this.update();
  }

  /** Adds a point (local metres) unless it is off the field. */
  add(x, z) {
    const loaded = this.terrain();
    if (!loaded) return false;
    if (this.track) this.clear(); // a click after a track's profile starts a path of one's own
    if (this.finished) { this.points = []; this.finished = false; }
    this.points.push([x, z]);
    this.update();
    return true;
  }

  undo() {
    this.finished = false;
    this.points.pop();
    this.update();
  }

  finish() {
    if (this.points.length >= (this.kind === 'area' ? 3 : 2)) this.finished = true;
    this.update();
  }

  clear() {
    if (this.track) this.kind = 'path';
    this.track = null;
    this.points = [];
    this.finished = false;
    this.overlay.setHover(null);
    this.update();
  }

  /** The ground was scaled by `k` (a new cell size): the points keep their place on the field. */
  rescale(k) {
    if (this.points.length === 0) return;
    this.points = this.points.map(([x, z]) => [x * k, z * k]);
    this.update();
  }

  /** A line from the address bar ({kind, points}, parseMeasureParam): shown finished, the tool on. */
  restore({ kind, points }) {
    this.active = true;
    this.kind = kind;
    this.points = points.map(([x, z]) => [x, z]);
    this.finished = true;
    this.update();
    return this.result;
  }

  /**
   * An overlay's track in the panel (app/overlay_tracks.js): its profile (measure/track_profile.js),
   * drawn over the track like a measured path; the tool is on, and a click starts a path of one's own.
   * @param {{name: string, profile: object}} track
   */
  showTrack(track) {
    this.active = true;
    this.kind = 'track';
    this.track = track;
    this.points = [];
    this.finished = true;
    this.update();
  }

  /** The terrain's heights changed (a tiled terrain's tiles came): what is measured is measured again. */
  heightsChanged() {
    if (this.active && this.points.length >= 2) this.update();
  }

  /** The sampler over the terrain on stage (full-resolution heights, its georeference). */
  sampler() {
    const loaded = this.terrain();
    return loaded ? fieldSampler(loaded.terrain, loaded.field.georef ?? null) : null;
  }

  /**
   * Measures the points again and hands the result to the overlay, the panel and the address
   * bar. result: { kind, points, finished, profile (the path's, or the outline's for an area),
   * area (measurePolygon) , error (why nothing could be measured) }.
   */
  update() {
    const sampler = this.sampler();
    const result = { active: this.active, kind: this.kind, points: this.points, finished: this.finished,
      profile: null, area: null, error: null, georef: sampler?.georef ?? null, track: this.track?.name ?? null };
    if (this.track && sampler && this.active) {
      result.profile = this.track.profile;
      this.overlay.setLine(result.profile.samples, []);
    } else if (sampler && this.active) {
      const line = this.kind === 'area' && this.points.length >= 3 ? [...this.points, this.points[0]] : this.points;
      try {
        if (line.length >= 2) result.profile = computeProfile(line, sampler);
        if (this.kind === 'area' && this.points.length >= 3) result.area = measurePolygon(this.points, sampler);
      } catch (error) {
        result.error = error.message;
      }
      const drawn = this.points.map(([x, z]) => [x, sampler.heightAt(x, z), z]).filter((p) => Number.isFinite(p[1]));
      this.overlay.setLine(result.profile?.samples ?? null, drawn);
    } else {
      this.overlay.setLine(null, []);
    }
    this.result = result;
    this.onResult(result);
    const enough = this.points.length >= (this.kind === 'area' ? 3 : 2) && !this.track;
    this.onParam(this.active && enough && sampler ? measureParam(this.kind, this.points, sampler.spacing) : null);
    this.requestRender();
  }

  /** The ground point under a pixel of the canvas (CSS pixels from its top left), or null. */
  pick(px, py) {
    const loaded = this.terrain();
    if (!loaded) return null;
    const rect = this.canvas.getBoundingClientRect();
    return pickGround(this.rig.active, px, py, rect.width, rect.height, loaded.terrain, loaded.world, this.settings.exaggeration);
  }

  /** A point where the view's centre meets the ground (Space): measuring without a pointer, moving with the keys. */
  addAtCentre() {
    const rect = this.canvas.getBoundingClientRect();
    if (this.finished || this.track) this.clear();
    const point = this.pick(rect.width / 2, rect.height / 2);
    if (point) this.add(point.x, point.z);
  }

  /** A click or tap at client (x, y) that did not drag. */
  clickAt(clientX, clientY, time) {
    const rect = this.canvas.getBoundingClientRect();
    const last = this.lastClick;
    const repeat = last && time - last.time < DOUBLE_MS && Math.hypot(clientX - last.x, clientY - last.y) < CLICK_PX;
    this.lastClick = { x: clientX, y: clientY, time };
    // The second press of a double click or tap finishes (the dblclick event does it for a mouse).
    if (repeat) {
      this.lastClick = null;
      this.finish();
      return;
    }
    // Between lines of one's own, a click on an overlay's line shows that line's profile.
    if ((this.points.length === 0 || this.finished || this.track) && this.lineAt?.(clientX, clientY)) return;
    const point = this.pick(clientX - rect.left, clientY - rect.top);
    if (point) this.add(point.x, point.z); // off the terrain: nothing
  }

  /** Pointer and keyboard input; the cameras keep theirs (a drag still moves them). */
  attach() {
    const canvas = this.canvas;
    const presses = new Map(); // pointerId -> {x, y, time, moved}
    let touchesSeen = 0;
    canvas.addEventListener('pointerdown', (e) => {
      if (!this.active || (e.pointerType === 'mouse' && e.button !== 0) || e.shiftKey) return;
      presses.set(e.pointerId, { x: e.clientX, y: e.clientY, time: e.timeStamp, moved: false });
      touchesSeen = e.pointerType === 'touch' ? Math.max(touchesSeen, presses.size) : 0;
    });
    canvas.addEventListener('pointermove', (e) => {
      const press = presses.get(e.pointerId);
      if (press && Math.hypot(e.clientX - press.x, e.clientY - press.y) > CLICK_PX) press.moved = true;
    });
    const release = (e, cancelled) => {
      const press = presses.get(e.pointerId);
      if (!press) return;
      presses.delete(e.pointerId);
      const multiTouch = e.pointerType === 'touch' && touchesSeen > 1;
      if (presses.size === 0) touchesSeen = 0;
      if (cancelled || press.moved || multiTouch || !this.active) return;
      if (e.pointerType === 'touch' && e.timeStamp - press.time > TAP_MS) return;
      this.clickAt(e.clientX, e.clientY, e.timeStamp);
    };
    canvas.addEventListener('pointerup', (e) => release(e, false));
    canvas.addEventListener('pointercancel', (e) => release(e, true));
    this.dom.on(this.dom.keyTarget, 'keydown', (e) => {
      if (isTyping(e) || e.ctrlKey || e.metaKey || e.altKey) return;
      const key = e.key.toLowerCase();
      if (key === 'm') this.toggle();
      else if (!this.active) return;
      else if (key === ' ') { e.preventDefault(); this.addAtCentre(); } // the keyboard's click: the ground at the view's centre
      else if (key === 'enter') this.finish();
      else if (key === 'backspace') { e.preventDefault(); this.undo(); }
      else if (key === 'escape') this.clear();
    });
  }
}
