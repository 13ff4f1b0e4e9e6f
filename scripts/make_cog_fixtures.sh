#!/bin/sh
# Writes the Cloud-Optimized GeoTIFFs of tests/fixtures/cog/ with GDAL's COG driver (run once by
# a developer; the tests read only the committed files and need no GDAL: apt-get install -y
# gdal-bin):
#   sh scripts/make_cog_fixtures.sh
# Sources and licences: tests/fixtures/cog/README.md.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out="$here/tests/fixtures/cog"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# GLOBE Himalaya: the 16-bit PNG holds h = v / 65535 * 8752 (public/terrain/globe_himalaya_2048.json);
# its quantum (0.13 m) is below half a metre, so rounding gives back GLOBE's whole metres, as int16.
cd "$here"
node --input-type=module -e "
import { decode } from 'fast-png';
import { readFileSync, writeFileSync } from 'node:fs';
const png = decode(readFileSync('public/terrain/globe_himalaya_2048.png'));
const meta = JSON.parse(readFileSync('public/terrain/globe_himalaya_2048.json', 'utf8'));
const out = new Int16Array(png.width * png.height);
for (let i = 0; i < out.length; i++) out[i] = Math.round(meta.min + (png.data[i] / 65535) * (meta.max - meta.min));
writeFileSync('$tmp/himalaya.i16', out);
"
# GDAL's view of a square raw int16 file of GLOBE cells (1/120 degree): NAME SIDE WEST NORTH
# [NODATA] writes $tmp/NAME.vrt over $tmp/NAME.i16; WEST and NORTH are cell edges.
raw_vrt() {
  nodata=${5:+"    <NoDataValue>$5</NoDataValue>
"}
  cat > "$tmp/$1.vrt" <<VRT
<VRTDataset rasterXSize="$2" rasterYSize="$2">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>$3, 0.008333333333333333, 0, $4, 0, -0.008333333333333333</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1" subClass="VRTRawRasterBand">
$nodata    <SourceFilename relativeToVRT="0">$tmp/$1.i16</SourceFilename>
    <ImageOffset>0</ImageOffset><PixelOffset>2</PixelOffset><LineOffset>$(($2 * 2))</LineOffset>
    <ByteOrder>LSB</ByteOrder>
  </VRTRasterBand>
</VRTDataset>
VRT
}
# Bounds of the .json are cell edges.
raw_vrt himalaya 2048 72.93333333333334 37.916666666666664
# The Jacksboro DEM as GDAL sees it (scripts/jacksboro_vrt.sh).
. "$here/scripts/jacksboro_vrt.sh"
jacksboro_vrt "$here" > "$tmp/jacksboro.vrt"

# A COG as a streaming viewer meets it: 256 x 256 tiles, deflate with the horizontal predictor,
# overviews down to one tile (512, 256), and a no-data value to report. The central 1024 x 1024
# samples only: the whole 2048 x 2048 field deflates to 6 MB, too much for the repository.
gdal_translate -q -of COG -srcwin 512 512 1024 1024 -a_nodata -32768 -co BLOCKSIZE=256 -co COMPRESS=DEFLATE \
  -co PREDICTOR=YES -co OVERVIEWS=AUTO "$tmp/himalaya.vrt" "$out/himalaya_1024_i16.tif"
# Heights stored scaled, as GDAL states them (metres = raw x 0.5 - 500): int16 half-metres offset
# by 500 m (raw = 2h + 1000), with statistics of the raw values. The central 512 x 512 samples.
gdal_translate -q -of COG -srcwin 768 768 512 512 -ot Int16 -scale 0 1000 1000 3000 -a_scale 0.5 -a_offset -500 -stats \
  -co BLOCKSIZE=256 -co COMPRESS=DEFLATE -co PREDICTOR=YES -co OVERVIEWS=AUTO "$tmp/himalaya.vrt" "$out/himalaya_512_scaled_i16.tif"
# Every codec and sample layout a published DEM comes in, on one 192 x 160 window (two tiles by
# two, the right and bottom partial; one overview): the tests decode each to the same heights.
mkdir -p "$out/codecs"
codec() { # NAME TYPE CREATION-OPTIONS...
  name=$1; type=$2; shift 2
  gdal_translate -q -of COG -srcwin 1000 900 192 160 -ot "$type" -co BLOCKSIZE=128 -co OVERVIEWS=AUTO "$@" \
    "$tmp/himalaya.vrt" "$out/codecs/$name.tif"
}
codec deflate_pred3_f32 Float32 -co COMPRESS=DEFLATE -co PREDICTOR=YES
codec lzw_pred2_i16 Int16 -co COMPRESS=LZW -co PREDICTOR=YES
codec zstd_i16 Int16 -co COMPRESS=ZSTD
codec lerc_f32 Float32 -co COMPRESS=LERC -co MAX_Z_ERROR=0
codec lerc_zstd_f32 Float32 -co COMPRESS=LERC_ZSTD -co MAX_Z_ERROR=0
codec lerc_deflate_f32 Float32 -co COMPRESS=LERC_DEFLATE -co MAX_Z_ERROR=0
codec packbits_u16 UInt16 -co COMPRESS=PACKBITS
codec none_i32_bigtiff Int32 -co COMPRESS=NONE -co BIGTIFF=YES
# A COG without overviews, float32, whose width and height are not whole tiles (edge tiles are partial).
gdal_translate -q -of COG -co BLOCKSIZE=128 -co COMPRESS=DEFLATE -co OVERVIEWS=NONE \
  "$tmp/jacksboro.vrt" "$out/jacksboro_403x344_f32_no_overviews.tif"
# A plain GeoTIFF in strips: not cloud-optimized (a view's rows span the whole width).
gdal_translate -q -of GTiff -co TILED=NO -co COMPRESS=DEFLATE \
  "$tmp/jacksboro.vrt" "$out/jacksboro_403x344_f32_strips.tif"
# No-data holes, as a lidar strip's edges or a DEM's voids leave them: 384 x 384 GLOBE samples
# (columns and rows 832..1215) with a rectangle (columns 120..219, rows 150..229) and a disc
# (centre column 290, row 90, radius 32) set to -32768, the no-data value; overviews averaged
# over the valid samples only (GDAL's AVERAGE), so they hold no-data only where all is void.
node --input-type=module -e "
import { readFileSync, writeFileSync } from 'node:fs';
const all = new Int16Array(readFileSync('$tmp/himalaya.i16').buffer.slice(0));
const side = 384, out = new Int16Array(side * side);
for (let r = 0; r < side; r++) for (let c = 0; c < side; c++) {
  const hole = (c >= 120 && c < 220 && r >= 150 && r < 230) || (c - 290) ** 2 + (r - 90) ** 2 <= 32 * 32;
  out[r * side + c] = hole ? -32768 : all[(832 + r) * 2048 + 832 + c];
}
writeFileSync('$tmp/voids.i16', out);
"
raw_vrt voids 384 79.86666666666667 30.983333333333334 -32768
gdal_translate -q -of COG -co BLOCKSIZE=128 -co COMPRESS=DEFLATE -co PREDICTOR=YES -co OVERVIEWS=AUTO \
  -co OVERVIEW_RESAMPLING=AVERAGE "$tmp/voids.vrt" "$out/himalaya_384_voids_i16.tif"
