// Where one viewer lives in the document. The page is one viewer filling the window; a host page
// may hold several (createViewer, <hexlod-viewer>). Each part finds its elements here, inside its
// own viewer's root, takes keys and drops where this says (the window for the page, the viewer's
// element in someone else's page, so that keys typed elsewhere stay theirs), and adds every
// listener outside its own elements through on(), which dispose() removes all at once.

export class ViewerDom {
  /**
   * @param {HTMLElement} root   the viewer's element (class "hexlod"), holding VIEWER_MARKUP
   * @param {{ page: boolean }} options  page: the viewer is the whole page (keys and drops on the window)
   */
  constructor(root, { page }) {
    this.root = root;
    this.page = page;
    this.keyTarget = page ? window : root;
    this.dropTarget = page ? window : root;
    this.aborter = new AbortController();
    this.disposed = false;
    if (!page) {
      // In someone else's page the viewer takes keys while it has the focus: a click on the
      // terrain or Tab gives it.
      root.tabIndex = 0;
      root.setAttribute('role', 'region');
      root.setAttribute('aria-label', 'terrain viewer: drag or use the keys to move, H for help');
      this.on(root, 'pointerdown', (e) => { if (e.target.id === 'view') root.focus({ preventScroll: true }); });
    }
  }

  /** The viewer's element with this id (ids are unique within a viewer, not across viewers). */
  byId(id) {
    return this.root.querySelector(`#${id}`);
  }

  /** target.addEventListener(type, handler), removed when the viewer is disposed. */
  on(target, type, handler, options = {}) {
    target.addEventListener(type, handler, { ...options, signal: this.aborter.signal });
  }

  /** Calls `handler` when the viewer's element changes size (the page: the window). */
  onResize(handler) {
    if (this.page) {
      this.on(window, 'resize', handler);
      return;
    }
    const observer = new ResizeObserver(() => handler());
    observer.observe(this.root);
    this.aborter.signal.addEventListener('abort', () => observer.disconnect());
  }

  /** Whether the viewer is small (a phone-sized page or element): panels start folded. */
  isSmall() {
    if (this.page) return window.matchMedia('(max-width: 800px), (max-height: 500px)').matches;
    return this.root.clientWidth <= 800 || this.root.clientHeight <= 500;
  }

  /** Removes every listener added through on(). */
  dispose() {
    this.disposed = true;
    this.aborter.abort();
  }
}
