// hexlod mesh: refines the hexagon mesh of a height field (view-independent to a maximum error,
// or for a camera) with the page's loaders and WASM core, and writes it as OBJ and figures as
// JSON.
import { writeFileSync } from 'node:fs';
import { basename } from 'node:path';
import {
  UsageError, parseOptions, parseNumber, parseTriple, parseViewport, parseCellSize, parseEmbedding,
  loadForCommand, FILE_OPTIONS, FILE_USAGE, parseFileOptions, extentOf, cameraFor, highestLevel, round,
} from './cli_common.js';
import { decodeFans, resolveDegenerate, clipToRectangle, writeObj } from './mesh_export.js';
import { textureCoordinates, materialImagePath, materialPathOf, writeMaterial, MATERIAL_NAME } from './mesh_texture.js';
import { readImageFiles } from './image_files.js';
import { RESTART_INDEX, STREAM_VERTEX_WORDS } from '../web/core/core.js';
import { locateImageFile } from '../web/imagery/image_location.js';
import { openCogInput, tilesForCommand, settleTiles } from './cog_input.js';
import { EARTH_FLAT, FLAT_EARTH, drawnPoint, drawnUp, earthShapeOf, geoCoordinates } from '../web/geo/index.js';

/** The most samples of a streamed field whose mesh error is measured (4 bytes each in the core). */
const MAX_MEASURED_SAMPLES = 2 ** 28;

export const MESH_USAGE = `usage: hexlod mesh <heightfield>... (--max-error M | --camera X,Y,Z --target X,Y,Z) [options]
  Several .hgt or GeoTIFF tiles of one grid make one mosaic. A Cloud-Optimized GeoTIFF (tiled,
  with overviews), by path or http(s) URL, is streamed: only the tiles the refinement needs
  are read (by slices of the file, or by HTTP Range requests).
  Refines the hexagon mesh until it converges (or for --budget-splits operations), prints a
  summary, and writes the mesh clipped to the data rectangle as OBJ and its figures as JSON.
  --max-error M         view-independent: every sample within M metres of the mesh
  --camera X,Y,Z        view-dependent: the eye, in metres (x east from the first column,
  --target X,Y,Z          y up = height, z south from the first row); --target is required
  --fov DEG             vertical field of view in degrees (default 60)
  --viewport WxH        viewport in pixels (default 1920x1080)
  --tau PX              screen-space error tolerance in pixels (default 1)
                        near plane: max(0.1 m, eye-target distance / 10000); far plane: 10 x
                        the distance from the eye to the field's farthest corner
  --cell-size DX[,DY]   metres between columns (and rows); default: from the file, else 1
  --budget-splits N     stop after one update of at most N operations (default: update until
                        converged, at most ${10000} updates)
  --embedding E         lattice embedding: exact (default) or shifted (the paper's)
  --obj FILE            write the mesh as Wavefront OBJ (y up, faces counter-clockwise from +y)
  --json FILE           write every figure as JSON
  --image FILE          drape an image (PNG, JPEG, WebP or 8-bit GeoTIFF) over the OBJ: every
                        vertex gets texture coordinates from the image's place on the field
                        (as the page drapes it), and NAME.mtl beside NAME.obj names the image;
                        placed by its world file or GeoTIFF tags, in the terrain's CRS; an
                        image without georeference is stretched over the field (needs --obj);
                        its .prj or GDAL .aux.xml beside it (IMAGE.prj, IMAGE.jpg.aux.xml) give
                        its CRS when the image names none
  --world-file FILE     the image's world file (default: IMAGE.jgw, .jpgw, .wld ... beside it)
  --earth E             the surface, as the page draws it: curved (the default for a
                        georeferenced field: a geographic grid on the WGS 84 ellipsoid, a
                        projected one wrapped on a sphere of the Earth's radius there; metres
                        east, up and south of the field's centre) or flat (the default without a
                        georeference: x east from the first column, z south from the first row).
                        The refinement bounds its error on that surface; --camera and --target
                        stay flat metres, placed on it as the page places its cameras
${FILE_USAGE}`;

const OPTIONS = {
  'max-error': 'string', camera: 'string', target: 'string', fov: 'string', viewport: 'string', tau: 'string',
  'cell-size': 'string', 'budget-splits': 'string', embedding: 'string', obj: 'string', json: 'string',
  image: 'string', 'world-file': 'string', earth: 'string',
  ...FILE_OPTIONS,
};
const MAX_UPDATES = 10000;

/** Checks the command line and turns it into settings; throws UsageError. */
export function meshSettings(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return { help: true };
  if (positionals.length === 0) throw new UsageError('mesh needs a height field file');
  const hasError = values['max-error'] !== undefined, hasCamera = values.camera !== undefined;
  if (hasError === hasCamera) {
    throw new UsageError(hasError ? 'give either --max-error or --camera, not both' : 'give --max-error M or --camera X,Y,Z with --target X,Y,Z');
  }
  if (!hasCamera) {
    for (const name of ['target', 'fov', 'viewport', 'tau']) {
      if (values[name] !== undefined) throw new UsageError(`--${name} goes with --camera, not --max-error`);
    }
  } else if (values.target === undefined) {
    throw new UsageError('--camera needs --target X,Y,Z');
  }
  const settings = {
    file: positionals[0],
    files: positionals, // one height field, or the tiles of a mosaic
    mode: hasCamera ? 'view' : 'max-error',
    embedding: parseEmbedding(values.embedding),
    cellSize: values['cell-size'] !== undefined ? parseCellSize(values['cell-size']) : null,
    fileOptions: parseFileOptions(values),
    budgetSplits: values['budget-splits'] !== undefined
      ? parseNumber('budget-splits', values['budget-splits'], { min: 1, integer: true, max: 2 ** 31 - 1 }) : null,
    obj: values.obj ?? null,
    json: values.json ?? null,
    image: values.image ?? null,
    worldFile: values['world-file'] ?? null,
    earth: values.earth ?? null, // null: as the page draws the field (curved when it has a georeference)
    earthShape: FLAT_EARTH,        // the surface itself (web/geo/earth_shape.js), once the field is read
  };
  if (settings.earth !== null && !['flat', 'curved'].includes(settings.earth)) {
    throw new UsageError(`--earth is flat or curved, not '${settings.earth}'`);
  }
  if (hasError) {
    settings.maxError = parseNumber('max-error', values['max-error'], { min: 0, exclusiveMin: true });
  } else {
    settings.eye = parseTriple('camera', values.camera);
    settings.target = parseTriple('target', values.target);
    if (settings.eye.every((v, i) => v === settings.target[i])) throw new UsageError('--camera and --target are the same point');
    settings.fov = values.fov !== undefined ? parseNumber('fov', values.fov, { min: 0, exclusiveMin: true, max: 179 }) : 60;
    settings.viewport = values.viewport !== undefined ? parseViewport(values.viewport) : [1920, 1080];
    settings.tau = values.tau !== undefined ? parseNumber('tau', values.tau, { min: 0, exclusiveMin: true }) : 1;
  }
  for (const [name, key] of [['obj', 'obj'], ['json', 'json'], ['image', 'image'], ['world-file', 'worldFile']]) {
    if (settings[key] === '') throw new UsageError(`--${name} needs a file name`);
  }
  if (settings.worldFile !== null && settings.image === null) throw new UsageError('--world-file goes with --image');
  if (settings.image !== null && settings.obj === null) throw new UsageError('--image needs --obj FILE (the texture coordinates go into the OBJ)');
  return settings;
}

/**
 * Refines as the settings say: resets the mesh, sets the mode, then either one update of at
 * most budgetSplits operations or updates until converged (at most MAX_UPDATES).
 * @returns {{updates, operations, splits, merges, converged, refineMs, coreMs, camera}}
 */
export async function refine(terrain, settings, tiles = null) {
  terrain.resetMesh(settings.embedding);
  const earth = settings.earthShape ?? FLAT_EARTH;
  terrain.setEarth(earth);
  let camera = null;
  if (settings.mode === 'view') {
    camera = cameraFor(terrain, settings.eye, settings.target, settings.fov, settings.viewport);
    if (earth.kind !== EARTH_FLAT) {
      // Placed on the curved Earth as the page places its cameras (web/cameras/on_the_earth.js).
      const [e, t] = [settings.eye, settings.target];
      camera = { ...camera, eye: drawnPoint(earth, ...e), target: drawnPoint(earth, ...t), up: drawnUp(earth, e[0], e[2]),
        far: camera.far * earth.stretch };
    }
    terrain.setLodCamera(camera);
    terrain.configure({ tauPx: settings.tau, maxErrorM: 0 });
  } else {
    terrain.configure({ maxErrorM: settings.maxError });
  }
  terrain.configure({ budgetMs: 0, maxOperations: settings.budgetSplits ?? 0 });
  const run = { updates: 0, operations: 0, splits: 0, merges: 0, converged: false, refineMs: 0, coreMs: 0, camera };
  const limit = settings.budgetSplits !== null ? 1 : MAX_UPDATES;
  if (tiles) {
    // A tiled COG: each update is a frame, so tiles that arrived change the heights.
    const start = performance.now();
    const settled = await settleTiles(terrain, tiles, limit, (figures) => {
      run.operations += figures.operations;
      run.splits += figures.splits;
      run.merges += figures.merges;
      run.coreMs += figures.updateMs;
    });
    run.refineMs = performance.now() - start;
    run.updates = settled.updates;
    run.converged = settled.converged;
    return run;
  }
  while (run.updates < limit) {
    const start = performance.now();
    const operations = terrain.updateLod();
    run.refineMs += performance.now() - start;
    const figures = { ...terrain.query() };
    run.updates += 1;
    run.operations += operations;
    run.splits += figures.splits;
    run.merges += figures.merges;
    run.coreMs += figures.updateMs;
    run.converged = figures.converged;
    if (run.converged) break;
  }
  return run;
}

/** Triangles and cells per level, from the fan stream's level offsets. */
function levelFigures(indices, levelOffsets) {
  const levels = [];
  for (let level = 0; level + 1 < levelOffsets.length; level++) {
    let cells = 0, triangles = 0, length = 0;
    for (let i = levelOffsets[level]; i < levelOffsets[level + 1]; i++) {
      if (indices[i] === RESTART_INDEX) {
        cells += 1;
        triangles += Math.max(0, length - 2);
        length = 0;
      } else {
        length += 1;
      }
    }
    if (cells > 0) levels.push({ level, cells, triangles });
  }
  return levels;
}

export async function mesh(args) {
  const settings = meshSettings(args);
  if (settings.help) {
    console.log(MESH_USAGE);
    return;
  }
  const cog = settings.files.length === 1 ? await openCogInput(settings.files[0]) : null;
  const { terrain, field, spacingX, spacingY, tiles } = cog
    ? await tilesForCommand(cog, settings.cellSize) : await loadForCommand(settings.files, settings.cellSize);
  // The surface, as the page draws this field; checked, as the image is, before refining.
  settings.earth ??= field.georef ? 'curved' : 'flat';
  if (settings.earth === 'curved') {
    if (!field.georef) throw new Error(`${field.source}: --earth curved needs a georeferenced field (this one has no CRS or geotransform)`);
    settings.earthShape = earthShapeOf(field.georef, terrain);
    if (settings.earthShape.kind === EARTH_FLAT) {
      throw new Error(`${field.source}: --earth curved needs the latitude of its centre, which its CRS (${field.georef.crs.label}) does not give here`);
    }
  }
  // The image is placed before refining, so a refused one costs no refinement.
  const image = settings.image !== null ? await placedImage(settings, terrain, field) : null;
  const run = await refine(terrain, settings, tiles);
  tiles?.close();

  const stats = { ...terrain.query() };
  // Copies: the views die at the next core call that grows memory.
  const levelView = terrain.levelView(false);
  const indices = levelView.indices.slice();
  const levelOffsets = Int32Array.from(levelView.levelOffsets);
  terrain.updateStream();
  const positions = terrain.stream().vertices.slice();
  const { triangles, fans } = decodeFans(indices);
  const levels = levelFigures(indices, levelOffsets);
  const bytes = terrain.query().memoryBytes; // now including the fan stream
  const hash = terrain.meshHash();
  // The error is a pass over every sample: a streamed field can be far past that (a world DEM at
  // 1″ has 8e11 samples), so one with more than MAX_MEASURED_SAMPLES is not measured (null).
  const measured = !tiles || terrain.width * terrain.height <= MAX_MEASURED_SAMPLES;
  const errorStored = measured ? terrain.measureError(true) : null;
  const errorOriginal = measured ? terrain.measureError(false) : null;

  const { xMax, zMax } = extentOf(terrain);
  const repaired = resolveDegenerate(positions, STREAM_VERTEX_WORDS, triangles);
  const clipped = clipToRectangle(positions, STREAM_VERTEX_WORDS, repaired.triangles, xMax, zMax);
  const name = field.source; // the file's name, or the mosaic's ("a.hgt + 3 more (mosaic 2 × 2)")
  const curved = settings.earthShape.kind !== EARTH_FLAT ? onTheEarth(clipped.vertices, field.georef, terrain, settings.earthShape) : null;
  if (settings.obj) {
    const comments = [
      `hexlod mesh of ${name}: ${clipped.vertices.length / 3} vertices, ${clipped.faces.length / 3} triangles`,
      curved ? `metres on the WGS 84 ellipsoid: x east, y up, z south of ${curved.centre} (heights as ellipsoidal)`
        : 'metres: x east from the first column, y up (height), z south from the first row',
      `clipped to the data rectangle [0, ${xMax}] x [0, ${zMax}]; faces counter-clockwise seen from +y`,
    ];
    let texture = null;
    if (image) {
      comments.push(`texture coordinates: ${image.file} ${image.location.placement.how}`);
      writeMaterial(image.mtl, image.map, [`hexlod mesh of ${name}: the draped image ${image.file}`]);
      texture = { uv: textureCoordinates(clipped.vertices, image.location.placement, spacingX, spacingY),
        mtllib: basename(image.mtl), material: MATERIAL_NAME };
    }
    if (curved) writeObj(settings.obj, { vertices: curved.vertices, faces: clipped.faces }, comments, null, null, texture);
    else writeObj(settings.obj, clipped, comments, xMax, zMax, texture);
  }

  const report = {
    file: name,
    width: terrain.width,
    height: terrain.height,
    spacingX,
    spacingY,
    spacingFromFile: settings.cellSize ? false : field.spacingFromFile,
    rectangle: { xMax, zMax },
    settings: {
      mode: settings.mode,
      embedding: settings.embedding,
      ...(settings.mode === 'max-error' ? { maxError: settings.maxError } : {
        camera: settings.eye,
        target: settings.target,
        up: run.camera.up,
        fovDeg: settings.fov,
        viewport: settings.viewport,
        tau: settings.tau,
        near: run.camera.near,
        far: run.camera.far,
      }),
      earth: settings.earth,
      budgetSplits: settings.budgetSplits,
      maxUpdates: settings.budgetSplits !== null ? 1 : MAX_UPDATES,
      cellSize: settings.cellSize,
    },
    converged: run.converged,
    updates: run.updates,
    operations: run.operations,
    splits: run.splits,
    merges: run.merges,
    refineMs: round(run.refineMs),
    refineCoreMs: round(run.coreMs),
    triangles: {
      drawn: stats.triangles,
      afterClipping: clipped.faces.length / 3,
      keptWhole: clipped.inside,
      cut: clipped.clipped,
      droppedOutside: clipped.dropped,
      zeroArea: repaired.degenerate,
    },
    cells: {
      total: stats.cells,
      fullHexagons: fans.full,
      boundarySemiHexagons: fans.boundarySemi,
      interiorSemiHexagons: fans.interiorSemi,
      other: fans.other,
    },
    vertices: { mesh: stats.vertices, stream: positions.length / STREAM_VERTEX_WORDS, obj: clipped.vertices.length / 3 },
    maxLevel: highestLevel(levelOffsets),
    finestLevel: stats.maxLevel,
    levels,
    bytes,
    bytesPerTriangle: round(bytes / Math.max(1, stats.triangles), 2),
    error: {
      stored: errorStored,
      original: errorOriginal,
    },
    hash,
    streamed: tiles ? { tiles: tiles.tilesIn, bytesFetched: tiles.bytesFetched, fileBytes: tiles.fileBytes,
      levels: field.levels } : null,
    image: image && {
      file: image.file,
      worldFile: image.worldFile,
      prj: image.prj,
      crs: image.location.georef?.crs.label ?? null,
      format: image.location.format,
      width: image.location.width,
      height: image.location.height,
      placement: image.location.placement.how,
      coverage: round(image.location.placement.coverage, 6),
      metresPerPixel: image.location.metresPerPixel === null ? null : round(image.location.metresPerPixel, 3),
      note: image.location.placement.note,
      mtl: image.mtl,
      mapKd: image.map,
    },
  };
  if (settings.json) writeFileSync(settings.json, JSON.stringify(report, null, 1) + '\n');

  const m = (v) => `${round(v, 3)} m`;
  const modeLine = settings.mode === 'max-error'
    ? `max error ${settings.maxError} m`
    : `camera ${settings.eye.join(',')} -> ${settings.target.join(',')}, fov ${settings.fov} deg, ` +
      `${settings.viewport.join('x')} px, tau ${settings.tau} px`;
  const refineLine = run.converged
    ? `converged after ${run.updates} update${run.updates === 1 ? '' : 's'}`
    : settings.budgetSplits !== null
      ? `stopped after 1 update (budget ${settings.budgetSplits} operations), not converged`
      : `NOT converged after ${run.updates} updates`;
  const lines = [
    `file      ${name}: ${terrain.width} x ${terrain.height} samples, spacing ${spacingX} x ${spacingY} m`,
    `mode      ${modeLine}, ${settings.embedding} embedding`,
    `refine    ${refineLine}: ${run.operations} operations (${run.splits} splits, ${run.merges} merges) in ${round(run.refineMs, 1)} ms`,
    `mesh      ${stats.triangles} triangles drawn, ${report.triangles.afterClipping} after clipping to the field; ` +
      `${stats.cells} cells (${fans.full} hexagons, ${fans.boundarySemi} boundary and ${fans.interiorSemi} interior semi-hexagons)`,
    `          ${stats.vertices} vertices; levels up to ${report.maxLevel} of ${stats.maxLevel}`,
    `memory    ${(bytes / 1048576).toFixed(2)} MB in the core, ${report.bytesPerTriangle} B per triangle`,
    measured
      ? `error     vs stored field: max ${m(errorStored.max)}, p99 ${m(errorStored.p99)}; ` +
        `vs original samples: max ${m(errorOriginal.max)}, p99 ${m(errorOriginal.p99)}`
      : `error     not measured: a pass over ${terrain.width * terrain.height} samples (streamed fields up to ${MAX_MEASURED_SAMPLES})`,
    `hash      ${hash}`,
  ];
  if (tiles) {
    const mb = (bytes) => (bytes / 1048576).toFixed(1);
    lines.push(`streamed  ${tiles.tilesIn} tiles; ${mb(tiles.bytesFetched)} of ${mb(tiles.fileBytes)} MB of the file read ` +
      `(a COG of ${field.levels} levels: heights come from the finest level read)`);
  }
  if (image) lines.push(`image     ${imageLine(image)}`);
  const written = [settings.obj && `${settings.obj} (${report.vertices.obj} vertices, ${report.triangles.afterClipping} faces)`,
    image?.mtl, settings.json]
    .filter(Boolean);
  if (written.length) lines.push(`wrote     ${written.join(', ')}`);
  console.log(lines.join('\n'));
}

/**
 * The image of --image placed on the loaded field, with the paths its material file gets.
 * Refusals (another CRS, off the field, a broken image or world file) throw its ImageError.
 */
async function placedImage(settings, terrain, field) {
  const { image, worldFile, prj, auxXml } = readImageFiles(settings.image, settings.worldFile);
  const location = await locateImageFile(image, { worldFile, prj, auxXml }, {
    width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY, georef: field.georef ?? null });
  if (location.placement.how === 'stretched') console.error(`hexlod: warning: ${image.name}: ${location.placement.note}`);
  for (const note of location.notes) console.error(`hexlod: warning: ${note}`);
  return { file: image.name, worldFile: worldFile?.name ?? null, prj: prj?.name ?? null, location,
    mtl: materialPathOf(settings.obj), map: materialImagePath(settings.obj, settings.image) };
}

/** The summary's line on the image: how it lies on the field. */
function imageLine({ file, worldFile, location }) {
  const { placement, width, height, metresPerPixel } = location;
  const how = placement.how === 'stretched'
    ? `STRETCHED over the whole field (${placement.note.split(':')[0]})`
    : `georeferenced${worldFile ? ` by ${worldFile}` : ''}, covers ${round(placement.coverage * 100, 1)} % of the field`;
  const ground = metresPerPixel === null ? '' : `, ${round(metresPerPixel, 1)} m a pixel`;
  return `${file}: ${width} x ${height} pixels, ${how}${ground}${placement.note && placement.how !== 'stretched' ? ` (${placement.note})` : ''}`;
}

/**
 * The mesh's vertices (x east and z south of the first sample, y height, metres) as the page
 * draws them on the curved Earth (web/geo/earth_shape.js): metres east, up and south of the
 * field's centre.
 * @returns {{ vertices: Float64Array, centre: string }}
 */
function onTheEarth(vertices, georef, terrain, earth) {
  const out = new Float64Array(vertices.length), p = [0, 0, 0];
  for (let i = 0; i < vertices.length; i += 3) {
    drawnPoint(earth, vertices[i], vertices[i + 1], vertices[i + 2], p);
    out[i] = p[0];
    out[i + 1] = p[1];
    out[i + 2] = p[2];
  }
  const c = geoCoordinates(georef, earth.originX, earth.originZ, terrain.spacingX, terrain.spacingY);
  const [lat0, lon0] = [c.lat, c.lon];
  const centre = `${Math.abs(lat0).toFixed(5)}° ${lat0 < 0 ? 'S' : 'N'} ${Math.abs(lon0).toFixed(5)}° ${lon0 < 0 ? 'W' : 'E'}`;
  return { vertices: out, centre };
}
