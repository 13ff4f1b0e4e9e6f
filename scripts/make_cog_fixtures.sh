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
# Bounds of the .json are cell edges; 1/120 degree cells.
cat > "$tmp/himalaya.vrt" <<VRT
<VRTDataset rasterXSize="2048" rasterYSize="2048">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>72.93333333333334, 0.008333333333333333, 0, 37.916666666666664, 0, -0.008333333333333333</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1" subClass="VRTRawRasterBand">
    <SourceFilename relativeToVRT="0">$tmp/himalaya.i16</SourceFilename>
    <ImageOffset>0</ImageOffset><PixelOffset>2</PixelOffset><LineOffset>4096</LineOffset>
    <ByteOrder>LSB</ByteOrder>
  </VRTRasterBand>
</VRTDataset>
VRT
# The Jacksboro DEM as GDAL sees it (scripts/jacksboro_vrt.sh).
. "$here/scripts/jacksboro_vrt.sh"
jacksboro_vrt "$here" > "$tmp/jacksboro.vrt"

# A COG as a streaming viewer meets it: 256 x 256 tiles, deflate with the horizontal predictor,
# overviews down to one tile (512, 256), and a no-data value to report. The central 1024 x 1024
# samples only: the whole 2048 x 2048 field deflates to 6 MB, too much for the repository.
gdal_translate -q -of COG -srcwin 512 512 1024 1024 -a_nodata -32768 -co BLOCKSIZE=256 -co COMPRESS=DEFLATE \
  -co PREDICTOR=YES -co OVERVIEWS=AUTO "$tmp/himalaya.vrt" "$out/himalaya_1024_i16.tif"
# A COG without overviews, float32, whose width and height are not whole tiles (edge tiles are partial).
gdal_translate -q -of COG -co BLOCKSIZE=128 -co COMPRESS=DEFLATE -co OVERVIEWS=NONE \
  "$tmp/jacksboro.vrt" "$out/jacksboro_403x344_f32_no_overviews.tif"
# A plain GeoTIFF in strips: not cloud-optimized (a view's rows span the whole width).
gdal_translate -q -of GTiff -co TILED=NO -co COMPRESS=DEFLATE \
  "$tmp/jacksboro.vrt" "$out/jacksboro_403x344_f32_strips.tif"
