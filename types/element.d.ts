// <hexlod-viewer> (web/api/element.js): import 'hexlod/element' defines it.
import type { Viewer } from './index.js';

export declare class HexlodViewerElement extends HTMLElement {
  /** The viewer once its first terrain is shown, else null. */
  viewer: Viewer | null;
  /** Resolves to the viewer once its first terrain is shown. */
  readonly ready: Promise<Viewer>;
}

declare global {
  interface HTMLElementTagNameMap { 'hexlod-viewer': HexlodViewerElement }
}
