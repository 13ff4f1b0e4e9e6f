// Copies fixed-size binary samples from a file into the sink a band of rows at a time,
// pausing between bands: the shared loop of the headerless formats (RAW/R16, .hgt, PGM P5).

const BAND_SAMPLES = 1 << 20;
const LITTLE_ENDIAN_HOST = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/**
 * @param {Uint8Array} bytes the file
 * @param {number} offset byte where sample 0 starts
 * @param {import('./pacing.js').SampleSink} sink destination (u8, u16 or i16)
 * @param {number} width
 * @param {number} height
 * @param {boolean} littleEndian byte order of 16-bit samples in the file
 */
export async function copyRows(bytes, offset, sink, width, height, littleEndian) {
  const bytesPerSample = sink.samples.BYTES_PER_ELEMENT;
  const rowsPerBand = Math.max(1, Math.floor(BAND_SAMPLES / width));
  for (let y0 = 0; y0 < height; y0 += rowsPerBand) {
    const first = y0 * width, count = Math.min(rowsPerBand, height - y0) * width;
    const samples = sink.samples;
    const src = bytes.subarray(offset + first * bytesPerSample, offset + (first + count) * bytesPerSample);
    if (bytesPerSample === 1 || littleEndian === LITTLE_ENDIAN_HOST) {
      // One byte copy: works whatever the alignment of the file's bytes.
      new Uint8Array(samples.buffer, samples.byteOffset + first * bytesPerSample, count * bytesPerSample).set(src);
    } else {
      // Swap byte order; storing into an Int16Array/Uint16Array keeps the low 16 bits (and sign).
      for (let i = 0, k = 0; i < count; i++, k += 2) samples[first + i] = (src[k] << 8) | src[k + 1];
    }
    await sink.pace(Math.min(height, y0 + rowsPerBand) / height);
  }
}
