#!/bin/sh
# Writes tests/fixtures/measure/everest_utm45.tif with GDAL (run once by a developer; the tests
# read only the committed file and the numbers below, and need no GDAL: apt-get install -y
# gdal-bin), and prints the reference coordinates tests/node/measure_coordinates.test.js holds:
#   sh scripts/make_measure_fixtures.sh
# The source is the real SRTM-derived 30" Everest DEM of tests/fixtures/formats/everest_i16_strips.tif
# (EPSG:4326), warped to UTM zone 45 north on WGS 84 (EPSG:32645) at 1000 m, bilinear: a
# projected field with a known place, to check eastings, northings and their latitudes and
# longitudes against GDAL's own transformation.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out="$here/tests/fixtures/measure"
mkdir -p "$out"
rm -f "$out/everest_utm45.tif"
gdalwarp -q -t_srs EPSG:32645 -tr 1000 1000 -tap -r bilinear -ot Int16 -dstnodata -32768 \
  -co COMPRESS=DEFLATE "$here/tests/fixtures/formats/everest_i16_strips.tif" "$out/everest_utm45.tif"
gdalinfo "$out/everest_utm45.tif" | grep -E '^(Size|Origin|Pixel Size)'
# Sample centres (column + 0.5, row + 0.5 in GDAL's pixel corner convention) -> easting, northing
# -> longitude, latitude.
for p in "0.5 0.5" "80.5 100.5"; do
  en=$(echo "$p" | gdaltransform "$out/everest_utm45.tif")
  ll=$(echo "$en" | gdaltransform -s_srs EPSG:32645 -t_srs EPSG:4326 -output_xy)
  echo "pixel $p -> $en -> lon lat $ll"
done
