// A profile as CSV text, for the page's export and `hexlod profile --csv`: the summary as
// '# ' comment lines first (spreadsheets and pandas skip them with comment='#'), then one header
// line and a row per sample. Columns: distance_m, x_m, z_m (local metres: x east, z south of the
// first sample), then the CRS coordinates when the field has a georeference (easting_m,
// northing_m, plus lon, lat where coordinates.js can invert the projection; lon, lat for a
// geographic CRS), and height_m. A track's profile (track_profile.js) adds what its file
// recorded: gps_elevation_m, time (ISO 8601) and vertex (the track's vertex at a vertex's row,
// empty between), and its recorded climb, duration and speeds in the summary.
import { geoCoordinates } from '../geo/index.js';

/**
 * @param {import('./profile.js').Profile} profile
 * @param {import('../geo/georef.js').Georef|null} [georef]
 * @param {number} [spacingX] metres between columns (default: the profile's)
 * @param {number} [spacingY] metres between rows
 * @returns {string} CSV text, lines ending in '\n'
 */
export function profileCsv(profile, georef = null, spacingX = profile.spacingX, spacingY = profile.spacingY) {
  const { samples, summary } = profile;
  const n = samples.distance.length;
  const at = (k) => geoCoordinates(georef, samples.x[k], samples.z[k], spacingX, spacingY);
  const first = n > 0 ? at(0) : null;
  const columns = ['distance_m', 'x_m', 'z_m'];
  let crsColumns = () => [];
  if (first?.geographic) {
    columns.push('lon', 'lat');
    crsColumns = (c) => [deg(c.lon), deg(c.lat)];
  } else if (first && first.lat !== null) {
    columns.push('easting_m', 'northing_m', 'lon', 'lat');
    crsColumns = (c) => [metres(c.easting), metres(c.northing), deg(c.lon), deg(c.lat)];
  } else if (first) {
    columns.push('easting_m', 'northing_m');
    crsColumns = (c) => [metres(c.easting), metres(c.northing)];
  }
  columns.push('height_m');
  const track = samples.vertex !== undefined;
  if (track) columns.push('gps_elevation_m', 'time', 'vertex');
  const lines = [
    `# length_m ${metres(summary.length)}`,
    `# length3d_m ${metres(summary.length3d)}`,
    `# gain_m ${metres(summary.gain)}`,
    `# loss_m ${metres(summary.loss)}`,
    `# min_height_m ${metres(summary.min)}`,
    `# max_height_m ${metres(summary.max)}`,
    `# mean_slope_deg ${summary.meanSlope.toFixed(2)}`,
    `# steepest_slope_deg ${summary.steepestSlope.toFixed(2)}`,
    `# samples ${n}`,
    `# crs ${georef ? georef.crs.label : 'none (local metres)'}`,
  ];
  if (track) {
    lines.push(`# gps_gain_m ${metres(summary.gpsGain)}`, `# gps_loss_m ${metres(summary.gpsLoss)}`);
    if (summary.duration !== null) lines.push(`# duration_s ${summary.duration.toFixed(1)}`);
    if (summary.averageSpeed !== null) lines.push(`# mean_speed_m_s ${summary.averageSpeed.toFixed(3)}`);
    if (summary.movingSpeed !== null) lines.push(`# moving_speed_m_s ${summary.movingSpeed.toFixed(3)}`);
  }
  if (profile.clipped) lines.push(`# clipped ${profile.clipped}`);
  if (profile.note) lines.push(`# note ${profile.note}`);
  lines.push(columns.join(','));
  for (let k = 0; k < n; k++) {
    const row = [metres(samples.distance[k]), metres(samples.x[k]), metres(samples.z[k])];
    if (georef) row.push(...crsColumns(at(k)));
    row.push(metres(samples.height[k]));
    if (track) {
      const t = samples.time[k];
      row.push(metres(samples.gpsElevation[k]), Number.isFinite(t) ? new Date(t).toISOString() : '', samples.vertex[k] >= 0 ? String(samples.vertex[k]) : '');
    }
    lines.push(row.join(','));
  }
  return lines.join('\n') + '\n';
}

// Millimetres and a nine-decimal degree (about a millimetre too); no-data stays empty.
const metres = (v) => (Number.isFinite(v) ? String(Number(v.toFixed(3))) : '');
const deg = (v) => (Number.isFinite(v) ? String(Number(v.toFixed(9))) : '');
