// What a person does with an overlay's track: its profile in the measuring panel (the
// terrain's heights along it at full resolution beside the file's own, its length, climb, time
// and speed: measure/track_profile.js), and a flight along it (cameras/track_follow.js on the
// camera path of overlays/track_flight.js) with its controls in the panel: speed or the track's
// own times, height, look-ahead, pause, stop.
import { computeTrackProfile } from '../measure/track_profile.js';
import { trackKeyframes } from '../overlays/track_flight.js';
import { TrackFollow } from '../cameras/track_follow.js';

const KMH = 1 / 3.6;

/** The longest path of an overlay's first line feature: [feature, path], or null. */
function mainTrack(overlay) {
  const feature = overlay.features.findIndex((f) => f.kind === 'line');
  if (feature < 0) return null;
  const paths = overlay.features[feature].paths;
  let path = 0;
  paths.forEach((p, k) => { if (p.x.length > paths[path].x.length) path = k; });
  return [feature, path];
}

/**
 * @param {{ measure: import('../ui/measure_tool.js').MeasureTool, rig: object, settings: object,
 *   folder: import('lil-gui').GUI, showStatus: Function, requestRender: () => void, syncPanel: () => void }} page
 *   folder: the panel's overlay folder, where the flight's controls appear while one flies
 */
export function createOverlayTracks({ measure, rig, settings, folder, showStatus, requestRender, syncPanel }) {
  const flight = { speedKmh: 120, byTimes: false, timeScale: 10, height: 300, lookAhead: 1500, paused: false };
  let controls = null, current = null; // current: the track flown, { layer, feature, path }

  function pathsOf(layer, feature, path) {
    if (!layer.placed) throw new Error(`${layer.name} is not on this terrain`);
    return { placed: layer.placed.features[feature].paths[path], source: layer.overlay.features[feature].paths[path] };
  }

  /** The camera path at the flight's settings, and how fast to play it. */
  function follow() {
    const { layer, feature, path } = current;
    const { placed, source } = pathsOf(layer, feature, path);
    const byTimes = flight.byTimes && source.t !== null;
    const keyframes = trackKeyframes(placed, source, (x, z) => layer.sampler.heightAt(x, z),
      { height: flight.height, lookAhead: flight.lookAhead, speed: byTimes ? null : flight.speedKmh * KMH,
        extentX: layer.sampler.extentX, extentZ: layer.sampler.extentZ });
    rig.verticalScale = settings.exaggeration;
    const was = rig.follow;
    rig.follow = new TrackFollow(keyframes, byTimes ? flight.timeScale : 1);
    if (was) rig.follow.seek(was.progress);
    rig.follow.playing = !flight.paused;
  }

  function showControls() {
    controls?.destroy();
    controls = folder.addFolder('fly along');
    const redo = () => { try { follow(); requestRender(); } catch (error) { showStatus(error.message, true); } };
    controls.add(flight, 'speedKmh', 5, 2000, 5).name('speed (km/h)').onFinishChange(redo);
    controls.add(flight, 'byTimes').name("by the track's times").onChange(redo);
    controls.add(flight, 'timeScale', 1, 200, 1).name('times ×').onFinishChange(redo);
    controls.add(flight, 'height', 2, 5000, 1).name('height (m)').onFinishChange(redo);
    controls.add(flight, 'lookAhead', 50, 20000, 50).name('look ahead (m)').onFinishChange(redo);
    controls.add(flight, 'paused').name('pause').onChange((paused) => {
      if (!rig.follow) return;
      rig.follow.playing = !paused && rig.follow.progress < 1;
      requestRender();
    }).listen();
    controls.add({ stop: () => tracks.stop() }, 'stop').name('stop flying');
  }

  const tracks = {
    /** The profile of one path of a line feature in the measuring panel. */
    showProfile(layer, feature, path) {
      try {
        const { placed, source } = pathsOf(layer, feature, path);
        const profile = computeTrackProfile(placed, source, layer.sampler);
        measure.showTrack({ name: layer.overlay.features[feature].name ?? layer.name, profile });
      } catch (error) {
        showStatus(`${layer.name}: ${error.message}`, true);
      }
    },

    /** The first line's profile (the panel's button). */
    profileOf(layer) {
      const main = mainTrack(layer.overlay);
      if (main) tracks.showProfile(layer, ...main);
    },

    /** Flies along the overlay's first line (the fly camera unless one walks). */
    flyAlong(layer, feature = null, path = 0) {
      const main = feature === null ? mainTrack(layer.overlay) : [feature, path];
      if (!main) return;
      current = { layer, feature: main[0], path: main[1] };
      flight.paused = false;
      rig.follow = null;
      try {
        if (rig.mode === 'orbit') rig.setMode('fly');
        follow();
      } catch (error) {
        current = null;
        showStatus(`${layer.name}: ${error.message}`, true);
        return;
      }
      showControls();
      syncPanel();
      showStatus(`Flying along ${layer.overlay.features[current.feature].name ?? layer.name} · pause or stop in the panel`);
      requestRender();
    },

    /** Ends the flight; the camera stays where it is. */
    stop() {
      rig.follow = null;
      current = null;
      controls?.destroy();
      controls = null;
    },

    /** The overlays changed: a flight along one that went ends. */
    overlaysChanged(overlays) {
      if (current && !overlays.includes(current.layer)) tracks.stop();
    },
  };
  return tracks;
}
