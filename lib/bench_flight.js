// The scripted flight of `hexlod bench` (lib/bench_command.js), which bench/refiner.js flies
// again in the native build: its cameras, and the heights it flies over in metres.
import { extentOf } from './cli_common.js';
import { seededRandom } from '../web/app/seeded_random.js';

/**
 * The flight: a straight line through the field's centre along a seeded heading, 80 % of the
 * shorter extent long, with a gentle sideways sway; `altitude` metres above the highest ground
 * under the next 10 frames; looking ahead and 10 degrees down.
 */
export function flightPath(terrain, { frames, seed, altitude, step = 0 }) {
  const rand = seededRandom(seed);
  const { xMax, zMax } = extentOf(terrain);
  const heading = rand() * 2 * Math.PI;
  const phase = rand() * 2 * Math.PI;
  const length = step > 0 ? Math.min(step * Math.max(frames - 1, 1), 0.8 * Math.min(xMax, zMax)) : 0.8 * Math.min(xMax, zMax);
  const sway = 0.0625 * length; // 5 % of the shorter side for the default length
  const [dx, dz] = [Math.cos(heading), Math.sin(heading)];
  const ground = [];
  const positions = [];
  for (let i = 0; i < frames + 10; i++) {
    const s = frames > 1 ? Math.min(i, frames - 1) / (frames - 1) - 0.5 : 0;
    const side = sway * Math.sin(2 * Math.PI * s + phase);
    const x = xMax / 2 + s * length * dx - side * dz;
    const z = zMax / 2 + s * length * dz + side * dx;
    positions.push([x, z]);
    ground.push(terrain.heightAt(x, z));
  }
  const pitch = (10 * Math.PI) / 180;
  const cameras = [];
  for (let i = 0; i < frames; i++) {
    const [x, z] = positions[i];
    const y = Math.max(...ground.slice(i, i + 11)) + altitude;
    const ahead = 1000;
    const target = [x + ahead * Math.cos(pitch) * dx, y - ahead * Math.sin(pitch), z + ahead * Math.cos(pitch) * dz];
    cameras.push({ eye: [x, y, z], target });
  }
  return { cameras, heading, length, step: frames > 1 ? length / (frames - 1) : 0 };
}

/** Heights of the field in metres as the core holds them (missing samples: the lowest). */
export function heightsInMetres(terrain, field) {
  const raw = terrain.samples();
  const heights = new Float32Array(raw.length);
  const nodata = field.nodata;
  for (let k = 0; k < raw.length; k++) {
    const v = raw[k];
    heights[k] = Number.isNaN(v) || !Number.isFinite(v) || (nodata !== null && v === nodata)
      ? terrain.minHeight : v * field.heightScale + field.heightOffset;
  }
  return heights;
}
