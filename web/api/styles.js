// The viewer's stylesheet (public/viewer.css) in a host page: linked once into its <head>, from
// beside this module, wherever the package is served from. lil-gui adds its own.
const STYLESHEET = new URL('../../public/viewer.css', import.meta.url).href;

/** Links the viewer's stylesheet into the document once. */
export function ensureStyles() {
  if (document.querySelector('link[data-hexlod]')) return;
  const link = Object.assign(document.createElement('link'), { rel: 'stylesheet', href: STYLESHEET });
  link.dataset.hexlod = '';
  document.head.append(link);
}
