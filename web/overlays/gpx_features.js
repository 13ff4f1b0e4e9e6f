// GPX 1.0 and 1.1 (topografix.com/GPX) as overlay features: each track (its segments as the
// paths of one line feature), each route, each waypoint, with <ele> and <time> per vertex.
//
// The DOM is walked here rather than through togeojson: togeojson skips a point whose lat or
// lon does not parse (a file with a bad vertex must say so) and keeps only the times that are
// present, so one vertex without a time shifts every later time onto the wrong vertex. The walk
// goes by sibling links, not getElementsByTagName, which xmldom makes slow on half a million
// points.
import { OverlayError } from './overlay_error.js';

const POINT_CHILDREN = new Set(['ele', 'time', 'extensions', 'link']);

/**
 * @param {Document} doc a parsed GPX document (its root element checked)
 * @returns {import('./geojson_features.js').Feature[]} tracks, routes, then waypoints, each in file order
 */
export function gpxFeatures(doc) {
  const root = doc.documentElement;
  const tracks = [], routes = [], waypoints = [];
  let counts = { trk: 0, rte: 0, wpt: 0 };
  for (const element of childElements(root)) {
    const tag = element.localName;
    if (!(tag in counts)) continue;
    const index = ++counts[tag];
    const properties = textProperties(element, tag === 'wpt' ? POINT_CHILDREN : new Set());
    const label = `${{ trk: 'track', rte: 'route', wpt: 'waypoint' }[tag]} ${index}${properties.name ? ` ("${properties.name}")` : ''}`;
    const name = properties.name ?? null;
    const feature = (kind, source, paths) => ({ kind, name, properties, altitude: 'clamp', source, paths, polygons: null });
    if (tag === 'wpt') {
      waypoints.push(feature('point', 'waypoint', [readPoints([element], label)]));
    } else if (tag === 'rte') {
      const path = readPoints(childElements(element, 'rtept'), label);
      if (path.x.length > 0) routes.push(feature('line', 'route', [path]));
    } else {
      const paths = childElements(element, 'trkseg').map((segment, k) => readPoints(childElements(segment, 'trkpt'), `${label}, segment ${k + 1}`));
      const kept = paths.filter((path) => path.x.length > 0);
      if (kept.length > 0) tracks.push(feature('line', 'track', kept));
    }
  }
  return [...tracks, ...routes, ...waypoints];
}

/** The child elements of an element, all or those of one local name. */
function childElements(element, localName = null) {
  const out = [];
  for (let node = element.firstChild; node; node = node.nextSibling) {
    if (node.nodeType === 1 && (localName === null || node.localName === localName)) out.push(node);
  }
  return out;
}

/** An element's text-only children as properties (<name>, <desc>, <type>, ...), but those skipped. */
function textProperties(element, skipped) {
  const properties = {};
  for (const child of childElements(element)) {
    const tag = child.localName;
    if (skipped.has(tag) || tag === 'trkseg' || tag === 'rtept' || childElements(child).length > 0) continue;
    const text = (child.textContent ?? '').trim();
    if (text !== '') properties[tag] = text;
  }
  return properties;
}

/** One Path of trkpt/rtept/wpt elements: lon, lat, <ele>, <time>. */
function readPoints(points, label) {
  const n = points.length;
  const x = new Float64Array(n), y = new Float64Array(n), z = new Float64Array(n), t = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    const point = points[k];
    const lon = attributeNumber(point, 'lon', k, label), lat = attributeNumber(point, 'lat', k, label);
    let ele = NaN, time = NaN;
    for (let child = point.firstChild; child; child = child.nextSibling) {
      if (child.nodeType !== 1) continue;
      if (child.localName === 'ele') ele = Number.parseFloat(child.textContent);
      else if (child.localName === 'time') time = Date.parse(child.textContent.trim());
    }
    x[k] = lon;
    y[k] = lat;
    z[k] = ele;
    t[k] = time;
  }
  return { x, y, z: z.some((v) => !Number.isNaN(v)) ? z : null, t: t.some((v) => !Number.isNaN(v)) ? t : null };
}

function attributeNumber(point, attribute, k, label) {
  const text = point.getAttribute(attribute);
  const value = text === null || text.trim() === '' ? NaN : Number(text);
  if (!Number.isFinite(value)) {
    throw new OverlayError(`${label}: <${point.localName}> ${k + 1} has ${attribute}=${text === null ? 'missing' : `"${text}"`}, not a number`);
  }
  return value;
}
