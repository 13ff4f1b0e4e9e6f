#!/bin/sh
# Writes the curved-Earth fixtures of tests/fixtures/earth/ with GDAL (run once by a developer;
# the tests read only the committed files and need no GDAL: apt-get install -y gdal-bin):
#   sh scripts/make_earth_fixtures.sh
# sea_level_10deg.tif: 10 by 10 degrees of longitude and latitude on the equator (EPSG:4326,
# 256 x 256 samples, cell edges at 5 W to 5 E and 5 S to 5 N), heights 0 to 2 m in a faint
# ripple: a sea-level plain 1,113 km across, whose horizon seen from 10 km up lies inside it.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out="$here/tests/fixtures/earth"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
node --input-type=module -e "
import { writeFileSync } from 'node:fs';
const n = 256, lines = ['ncols 256', 'nrows 256', 'xllcorner -5', 'yllcorner -5', 'cellsize 0.0390625', 'NODATA_value -9999'];
for (let i = 0; i < n; i++) {
  const row = [];
  for (let j = 0; j < n; j++) row.push((1 + Math.sin(j / 7) * Math.cos(i / 9)).toFixed(2));
  lines.push(row.join(' '));
}
writeFileSync('$tmp/sea.asc', lines.join('\n') + '\n');
"
gdal_translate -q -of GTiff -a_srs EPSG:4326 -ot Float32 -co COMPRESS=DEFLATE -co PREDICTOR=3 "$tmp/sea.asc" "$out/sea_level_10deg.tif"
