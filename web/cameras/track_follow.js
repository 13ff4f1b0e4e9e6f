// "Fly along": the fly or walk camera follows a track's camera path (overlays/track_flight.js:
// keyframes at a height above the ground, looking a distance ahead), played at a speed, or by
// the track's own times faster or slower, and paused and resumed. The fly camera takes the
// path's eye; the walk camera walks the track itself (its eye height above the ground) and
// looks the same way. The rig steps it every frame while it plays (rig.js step); a frame
// allocates nothing.

export class TrackFollow {
  /**
   * @param {Array<{time: number, position: number[], target: number[]}>} keyframes seconds; metres,
   *   heights unexaggerated (the flight files' convention)
   * @param {number} rate seconds of the path a second of the screen (1: the keyframes' own pace)
   */
  constructor(keyframes, rate = 1) {
    const n = keyframes.length;
    this.times = Float64Array.from(keyframes, (k) => k.time);
    this.values = new Float64Array(n * 6);
    keyframes.forEach((k, i) => this.values.set([...k.position, ...k.target], 6 * i));
    this.sample = new Float64Array(6);
    this.time = this.times[0];
    this.rate = rate;
    this.playing = true;
    this.index = 0; // the keyframe at or before this.time
  }

  get duration() { return this.times[this.times.length - 1]; }

  /** Share of the path behind, 0..1. */
  get progress() { return this.duration > 0 ? this.time / this.duration : 1; }

  /** Goes on by `seconds` of the screen and poses the camera; stops at the end. */
  step(seconds, camera, verticalScale) {
    if (this.playing) this.time = Math.min(this.duration, this.time + seconds * this.rate);
    if (this.time >= this.duration) this.playing = false;
    this.pose(camera, verticalScale);
  }

  /** Moves to a share of the path (0..1). */
  seek(progress) {
    this.time = Math.min(1, Math.max(0, progress)) * this.duration;
    this.index = 0;
  }

  /** The path at this.time: eye and target, linear between keyframes (they lie close together). */
  at() {
    const t = this.times, v = this.values, out = this.sample;
    while (this.index > 0 && t[this.index] > this.time) this.index--;
    while (this.index + 1 < t.length && t[this.index + 1] <= this.time) this.index++;
    const i = this.index, j = Math.min(i + 1, t.length - 1);
    const s = j > i ? (this.time - t[i]) / (t[j] - t[i]) : 0;
    for (let c = 0; c < 6; c++) out[c] = v[6 * i + c] + (v[6 * j + c] - v[6 * i + c]) * s;
    return out;
  }

  /** Puts the camera on the path: the fly camera at its eye, the walk camera on the track below it. */
  pose(camera, verticalScale) {
    const p = this.at();
    if (camera.mode === 'walk') camera.standAt(p[0], p[2]);
    else camera.position.set([p[0], p[1] * verticalScale, p[2]]);
    // The walk looks level along the track: the target at its eye height over the ground ahead.
    const targetY = camera.mode === 'walk' ? camera.world.floor(p[3], p[5]) + camera.eyeHeight : p[4] * verticalScale;
    const dx = p[3] - camera.position[0], dy = targetY - camera.position[1], dz = p[5] - camera.position[2];
    const length = Math.hypot(dx, dy, dz);
    if (!(length > 0)) return;
    camera.yaw = Math.atan2(-dx, -dz);
    camera.pitch = Math.max(-1.55, Math.min(1.55, Math.asin(dy / length)));
  }
}
