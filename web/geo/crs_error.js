// A CRS that cannot be read from a file (a .prj, an .aux.xml, a GeoTIFF's citation): the
// message names the file and what was wrong. Callers decide whether it refuses the file or is a
// note beside it (a sidecar never stops a drop).
export class CrsError extends Error {
  constructor(message) {
    super(message);
    this.name = 'CrsError';
  }
}
