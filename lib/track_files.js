// Tracks made up for benchmarks and tests of scale: a GPX 1.1 track of any number of points on a
// smooth closed curve (a Lissajous figure) inside a box of longitude and latitude, with
// elevations and times, as a GPS logger writes them (one <trkpt> a line).

/**
 * @param {number} count points
 * @param {{west: number, east: number, south: number, north: number}} box degrees; the curve fills its middle 80 %
 * @param {{name?: string, start?: number, secondsPerPoint?: number}} [options] start: ms since the epoch
 * @returns {string} the GPX document
 */
export function lissajousGpx(count, box, { name = 'lissajous', start = Date.UTC(2026, 5, 1, 6), secondsPerPoint = 1 } = {}) {
  const cx = (box.west + box.east) / 2, cy = (box.south + box.north) / 2;
  const rx = 0.4 * (box.east - box.west), ry = 0.4 * (box.north - box.south);
  const parts = [`<?xml version="1.0" encoding="UTF-8"?>\n<gpx version="1.1" creator="hexlod" xmlns="http://www.topografix.com/GPX/1/1">\n<trk><name>${name}</name><trkseg>\n`];
  for (let k = 0; k < count; k++) {
    const t = (2 * Math.PI * k) / count;
    const lon = cx + rx * Math.sin(3 * t), lat = cy + ry * Math.sin(2 * t + 0.5);
    const time = new Date(start + k * secondsPerPoint * 1000).toISOString();
    parts.push(`<trkpt lat="${lat.toFixed(7)}" lon="${lon.toFixed(7)}"><ele>${(3000 + 500 * Math.sin(5 * t)).toFixed(1)}</ele><time>${time}</time></trkpt>\n`);
  }
  parts.push('</trkseg></trk>\n</gpx>\n');
  return parts.join('');
}
