// Files dropped or picked (File objects; a dropped folder comes as its files), as one load. Which
// file is what (web/imagery/drop_roles.js) decides what the drop does to the layer list: a
// height field (with its sidecars), or the tiles of a mosaic (web/loaders/mosaic.js), replaces
// the terrain; each image (with its world file, .prj and .aux.xml) is draped over the terrain,
// the new one or the one on screen, in the order they came; GPX, KML, KMZ and GeoJSON overlays
// are drawn over it (or wait for a terrain when none is shown). Files that are neither are skipped,
// and the status line names them. A colour PNG opened alone is a height field when its first
// row reads as heights, else an image.
import { dropRoles } from '../imagery/drop_roles.js';
import { ImageError } from '../imagery/image_error.js';
import { OverlayError } from '../overlays/overlay_error.js';
import { detectPngEncoding, hasPngSignature } from '../loaders/png.js';
import { shouldOpenTiled } from './tiled_open.js';

// The PNG colours menu: 'image' drapes a colour PNG; an encoding makes it heights.
const PNG_CHOICE = { auto: 'auto', image: 'image', 'terrain-rgb': 'height', terrarium: 'height' };
const HEAD_BYTES = 64 * 1024; // of each opened file, to tell height fields from images
const MB = 2 ** 20;

/**
 * @param {{ loads: import('./load_sequence.js').LoadSequence, indicator: object, settings: object,
 *   layers: import('../app/layers.js').Layers, opening: ReturnType<import('./terrain_opening.js').createTerrainOpening>,
 *   drape: (image: {name: string, blob: Blob}, sidecars: object, options?: object) => Promise<object|null>,
 *   showStatus: (message: string, isError?: boolean) => void, encoding: () => string }} page
 *   drape: an image and its sidecars ({ worldFile, prj, auxXml }, each { name, blob } or null)
 *   onto the terrain on screen (app/image_stage.js); with { throwRefusal: true } a refusal is thrown;
 *   addOverlay: a { name, bytes } overlay file over the terrain (app/overlay_stage.js), likewise
 * @returns {(list: FileList|File[]) => Promise<string>} opens them; resolves to 'shown', 'failed' or 'cancelled'
 */
export function pickedFilesOpener({ loads, indicator, settings, layers, opening, drape, addOverlay, showStatus, encoding }) {
  const { decode, openTiles, failed, cancelled } = opening;

  /** The drop's files as { name, head } (the first bytes) and, for a colour PNG alone, whether it holds heights. */
  async function look(picked) {
    const heads = await Promise.all(picked.map(async (file) => ({ name: file.name, head: new Uint8Array(await file.slice(0, HEAD_BYTES).arrayBuffer()) })));
    // A colour PNG's first row is read only when the roles need it (it alone, 8-bit colour by
    // its header); the bytes read then are the ones decoded.
    const heightPng = new Set(), read = new Map();
    const [only] = heads;
    if (picked.length === 1 && encoding() === 'auto' && hasPngSignature(only.head) && only.head[24] === 8 && [2, 3, 6].includes(only.head[25])) {
      read.set(0, new Uint8Array(await picked[0].arrayBuffer()));
      if (await detectPngEncoding(read.get(0), only.name)) heightPng.add(only.name);
    }
    return { heads, read, heightPng };
  }

  return (list) => {
    const picked = [...list];
    return loads.run(async (signal) => {
      indicator.start(true);
      const names = picked.map((f) => f.name).join(' + ');
      showStatus(`Loading ${names}…`);
      const { heads, read, heightPng } = await look(picked);
      let roles;
      try {
        roles = dropRoles(heads, { pngAsImage: PNG_CHOICE[encoding()], colourPngIsHeight: (f) => heightPng.has(f.name) });
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        return failed(error.message);
      }
      const file = (i) => (i === null ? null : { name: picked[i].name, blob: picked[i] });
      const images = roles.images.map(({ image, sidecars }) => ({ image: file(image),
        sidecars: { worldFile: file(sidecars.worldFile), prj: file(sidecars.prj), auxXml: file(sidecars.auxXml) } }));
      const skipped = roles.skipped.length ? `skipped ${roles.skipped.map(({ file: i, why }) => `${picked[i].name} (${why})`).join(', ')}` : null;
      if (roles.field.length === 0 && images.length > 0 && !layers.ground) {
        return failed(`${images.map((i) => i.image.name).join(', ') || names}: an image is draped over a terrain, and none is shown; open a height field with it or first`);
      }
      // A lone COG streams from the File (read by slices, never whole); any other height field loads whole.
      const lone = roles.field.length === 1 && images.length === 0 && roles.overlays.length === 0;
      if (lone && await shouldOpenTiled(picked[roles.field[0]], heads[roles.field[0]].head, settings.tileCacheMB * MB)) {
        if (signal.aborted) return cancelled(signal, names);
        const name = picked[roles.field[0]].name;
        try {
          const outcome = await openTiles(picked[roles.field[0]], name, signal, null);
          if (outcome === 'shown' && skipped) showStatus(skipped);
          return outcome;
        } catch (error) {
          return signal.aborted ? cancelled(signal, names) : failed(`${name}: cannot stream it (${error.message})`);
        }
      }
      if (roles.field.length > 0) {
        const files = await Promise.all(roles.field.map(async (i) => ({ name: picked[i].name, bytes: read.get(i) ?? new Uint8Array(await picked[i].arrayBuffer()) })));
        if (signal.aborted) return cancelled(signal, names);
        const outcome = await decode(files, {}, signal, null, false);
        if (outcome !== 'shown') return outcome;
      }
      // Each image in turn, in drop order; then one status line for the whole drop: refusals,
      // notes, and what was skipped.
      const refused = [], draped = [], notes = roles.field.length > 0 ? [...(layers.ground?.field.notes ?? [])] : [];
      for (const { image, sidecars } of images) {
        if (signal.aborted) break;
        try {
          const opened = await drape(image, sidecars, { throwRefusal: true });
          draped.push(image.name);
          if (opened?.note) notes.push(`${image.name}: ${opened.note}`);
        } catch (error) {
          if (!(error instanceof ImageError)) throw error;
          refused.push(error.message);
        }
      }
      // Each overlay in turn, over the terrain now on screen.
      const added = [];
      let overlayRefused = false;
      for (const i of roles.overlays) {
        if (signal.aborted) break;
        try {
          const bytes = read.get(i) ?? new Uint8Array(await picked[i].arrayBuffer());
          await addOverlay({ name: picked[i].name, bytes }, { throwRefusal: true });
          added.push(picked[i].name);
        } catch (error) {
          if (!(error instanceof OverlayError)) throw error;
          refused.push(error.message);
          overlayRefused = true; // said by nobody yet
        }
      }
      // A lone refusal is in the status line already, as the image stage says it.
      const said = [...refused, ...notes, skipped].filter(Boolean);
      // An overlay's own report (what it drew, what lies off the terrain) stands when it is all there is to say.
      const overlayOnly = added.length > 0 && refused.length === 0 && images.length === 0 && !skipped;
      if (!overlayOnly && (said.length > 1 || (said.length === 1 && refused.length === 0) || overlayRefused)) {
        const kept = layers.images.at(-1)?.image?.name;
        const stays = refused.length && kept && !draped.includes(kept) ? ` (${kept} stays)` : '';
        showStatus(`${said.join(' · ')}${stays}`, refused.length > 0);
      }
      return refused.length ? 'failed' : 'shown';
    });
  };
}
