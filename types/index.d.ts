// Types of hexlod's JS API (web/api/index.js). Positions are metres in the terrain's frame:
// x east from the first sample, y up (heights as drawn, with the exaggeration), z south (rows).

/** Settings by the settings table's keys, as in the panel and the address bar. */
export interface ViewerSettings {
  /** Screen-space error bound in pixels (0.25–16). */
  tau?: number;
  /** Time budget of the level-of-detail update per frame, ms (0.5–50). */
  budgetMs?: number;
  freeze?: boolean;
  maxOperations?: number;
  maxTriangles?: number;
  autoTau?: boolean;
  geomorph?: boolean;
  culling?: boolean;
  backfaceCulling?: boolean;
  /** Vertical exaggeration (0.1–20). */
  exaggeration?: number;
  wireframe?: boolean;
  colorByLevel?: boolean;
  eyeHeight?: number;
  shading?: 'natural' | 'hypsometric' | 'slope' | 'hillshade' | 'plain';
  sunAzimuth?: number;
  sunElevation?: number;
  shadows?: boolean;
  occlusion?: boolean;
  normals?: 'field' | 'mesh';
  imageOpacity?: number;
  imageUnlit?: boolean;
  contours?: boolean;
  /** Metres between contour lines, or 'auto'. */
  contourInterval?: number | 'auto';
  embedding?: 'exact' | 'shifted';
  cellSize?: number;
  layout?: 'triangles' | 'fans';
  urlTimeout?: number;
  urlMaxMB?: number;
  tileCacheMB?: number;
  timing?: boolean;
  normalTile?: number;
  imageTile?: number;
}

export interface EventHandlers {
  loaded?: (event: LoadedEvent) => void;
  frame?: (event: FrameEvent) => void;
  error?: (event: ErrorEvent) => void;
  pick?: (event: PickEvent) => void;
}

export interface ViewerOptions extends ViewerSettings {
  /** A height field's URL instead of the default terrain. */
  src?: string | null;
  /** An image's URL to drape over it. */
  image?: string;
  images?: string[];
  /** GPX, KML, KMZ or GeoJSON URLs. */
  overlays?: string[];
  /** false: a bare canvas, without the panel, the figures (HUD) and the file bar. */
  ui?: boolean;
  /** Handlers attached before the first terrain loads. */
  on?: EventHandlers;
}

export interface TerrainInfo {
  name: string;
  width: number;
  height: number;
  spacingX: number;
  spacingY: number;
  minHeight: number;
  maxHeight: number;
  /** 'EPSG:32645' and the like, or null without a georeference. */
  crs: string | null;
  centre: { lon: number; lat: number } | null;
  tiled: boolean;
}

export interface LoadedEvent { terrain: TerrainInfo | null }
export interface FrameEvent { frames: number; triangles: number; converged: boolean; tau: number; frameMs: number }
export interface ErrorEvent { message: string }
export interface PickEvent { x: number; z: number; height: number; slope?: number; place?: string }
export type EventName = 'loaded' | 'frame' | 'error' | 'pick';
export interface EventMap { loaded: LoadedEvent; frame: FrameEvent; error: ErrorEvent; pick: PickEvent }

export type Vec3 = [number, number, number] | number[] | Float32Array;

export interface CameraPose { mode: 'orbit' | 'fly' | 'walk'; position: number[]; target: number[] }

export interface ViewerCamera {
  /** Resolves to true on arrival, false when stopped (another flight, a drag). Instant with prefers-reduced-motion. */
  flyTo(view: { position: Vec3; target: Vec3 }, options?: { seconds?: number }): Promise<boolean>;
  get(): CameraPose;
  /** The opening view again. */
  reset(): void;
}

export interface Viewer {
  readonly camera: ViewerCamera;
  readonly terrain: TerrainInfo | null;
  readonly settings: Required<ViewerSettings>;
  readonly canvas: HTMLCanvasElement;
  readonly root: HTMLElement;
  /** Opens a height field (a URL, or Files as if dropped together); the old terrain stays when it is refused. */
  open(source: string | File | File[]): Promise<TerrainInfo | null>;
  /** Drapes an image (a URL, or a File with its world file and .prj). */
  drape(source: string | File | File[]): Promise<TerrainInfo | null>;
  addOverlay(source: string | File): Promise<{ name: string; features: number }>;
  /** Changes a setting live; a TypeError or RangeError for a bad value. */
  set<K extends keyof ViewerSettings>(key: K, value: NonNullable<ViewerSettings[K]>): void;
  on<K extends EventName>(type: K, handler: (event: EventMap[K]) => void): () => void;
  off<K extends EventName>(type: K, handler: (event: EventMap[K]) => void): void;
  /** The view as a PNG at scale × the canvas's size. */
  screenshot(options?: { scale?: 1 | 2 | 3 | 4 }): Promise<Blob>;
  memory(): { wasmBytes: number };
  /** Frees the WebAssembly memory, the GL context, every listener and the viewer's elements. */
  dispose(): void;
}

export declare const VERSION: string;
export declare function createViewer(element: HTMLElement, options?: ViewerOptions): Promise<Viewer>;
