#!/bin/sh
# Writes the GeoTIFF tiles of tests/fixtures/mosaic/ with GDAL (run once by a developer; the
# tests read only the committed files and need no GDAL: apt-get install -y gdal-bin):
#   sh scripts/make_mosaic_fixtures.sh
# The source is the real USGS NED 3" DEM of tests/fixtures/jacksboro_fault.f32 (403 x 344
# float32, its .json gives the bounds). Its north-west 257 x 193 samples are the un-cut field
# (source.tif); the tiles are cut from the same samples with gdal_translate -srcwin, so a
# correct mosaic equals source.tif sample for sample. See tests/fixtures/mosaic/README.md.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out="$here/tests/fixtures/mosaic"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# The Jacksboro DEM as GDAL sees it (scripts/jacksboro_vrt.sh).
. "$here/scripts/jacksboro_vrt.sh"
jacksboro_vrt "$here" > "$tmp/jacksboro.vrt"
cut() { # name xoff yoff width height [extra gdal_translate options]
  name=$1; shift; x=$1; y=$2; w=$3; h=$4; shift 4
  gdal_translate -q -of GTiff -co COMPRESS=DEFLATE -srcwin "$x" "$y" "$w" "$h" "$@" "$tmp/jacksboro.vrt" "$out/$name"
}
cut source.tif 0 0 257 193
# 2 x 2 tiles that share their edge samples (each 129 x 97; column 128 and row 96 are in two tiles).
cut shared_nw.tif 0 0 129 97
cut shared_ne.tif 128 0 129 97
cut shared_sw.tif 0 96 129 97
cut shared_se.tif 128 96 129 97
# Two tiles that abut: no sample in both.
cut abut_w.tif 0 0 128 193
cut abut_e.tif 128 0 129 193
# Tiles that cannot join shared_nw.tif: every second sample (twice the spacing), another CRS
# label for the same numbers (NAD83), and a grid shifted by half a sample eastwards.
cut coarse_ne.tif 128 0 129 97 -outsize 65 49 -r nearest
cut nad83_ne.tif 128 0 129 97 -a_srs EPSG:4269
west=$(echo "-84.41375 + 128.5 / 1200" | bc -l); east=$(echo "$west + 129 / 1200" | bc -l)
cut offgrid_ne.tif 128 0 129 97 -a_ullr "$west" 36.73291666666667 "$east" "$(echo "36.73291666666667 - 97 / 1200" | bc -l)"
# The north tiles again, their heights stated as raw x 0.5 + 10 m (GDAL's scale and offset; the
# same raw samples): a mosaic of them keeps the scale, and one beside an unscaled tile is refused.
cut scaled_nw.tif 0 0 129 97 -a_scale 0.5 -a_offset 10
cut scaled_ne.tif 128 0 129 97 -a_scale 0.5 -a_offset 10
rm -f "$out"/*.aux.xml
ls -l "$out"
