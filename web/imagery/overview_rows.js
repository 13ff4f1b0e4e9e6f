// A smaller copy of an image made while its rows stream past (GeoTIFF bands, top to bottom):
// each overview texel is the mean of the image pixels that fall in it (a box filter), and each
// overview row is handed on as soon as its last image row has arrived. Only one overview row
// of sums is held, never the image or the whole overview.

export class OverviewRows {
  /**
   * @param {number} width image pixels
   * @param {number} height
   * @param {number} overviewWidth texels (at most width)
   * @param {number} overviewHeight (at most height)
   * @param {(row: number, rgba: Uint8Array) => void} emitRow gets each overview row once, in
   *   order (the array is reused: copy it to keep it)
   */
  constructor(width, height, overviewWidth, overviewHeight, emitRow) {
    Object.assign(this, { width, height, overviewWidth, overviewHeight, emitRow });
    this.columnOf = new Uint32Array(width);
    this.columnCount = new Uint32Array(overviewWidth);
    for (let x = 0; x < width; x++) {
      this.columnOf[x] = Math.min(overviewWidth - 1, Math.floor((x * overviewWidth) / width));
      this.columnCount[this.columnOf[x]]++;
    }
    this.sums = new Uint32Array(overviewWidth * 4);
    this.out = new Uint8Array(overviewWidth * 4);
    this.row = 0;       // the overview row being summed
    this.rowsIn = 0;    // image rows summed into it
    this.nextImageRow = 0;
  }

  /** Image rows y..y+rows-1 (RGBA, width * rows * 4 bytes), the next ones in order. */
  add(y, rows, rgba) {
    if (y !== this.nextImageRow) throw new Error(`overview: rows must come in order (got ${y}, expected ${this.nextImageRow})`);
    for (let r = 0; r < rows; r++) {
      const row = Math.min(this.overviewHeight - 1, Math.floor(((y + r) * this.overviewHeight) / this.height));
      if (row !== this.row) this.flush(row);
      const sums = this.sums, columnOf = this.columnOf;
      for (let x = 0, i = r * this.width * 4; x < this.width; x++, i += 4) {
        const o = columnOf[x] * 4;
        sums[o] += rgba[i]; sums[o + 1] += rgba[i + 1]; sums[o + 2] += rgba[i + 2]; sums[o + 3] += rgba[i + 3];
      }
      this.rowsIn++;
    }
    this.nextImageRow = y + rows;
  }

  /** After the last image row: the last overview row. */
  finish() {
    this.flush(this.overviewHeight);
  }

  flush(nextRow) {
    if (this.rowsIn > 0) {
      for (let c = 0; c < this.overviewWidth; c++) {
        const n = this.columnCount[c] * this.rowsIn;
        for (let k = 0; k < 4; k++) this.out[c * 4 + k] = Math.round(this.sums[c * 4 + k] / n);
      }
      this.emitRow(this.row, this.out);
    }
    this.sums.fill(0);
    this.rowsIn = 0;
    this.row = nextRow;
  }
}
