#!/bin/sh
# Writes the web map tiles of tests/fixtures/webtiles/ with GDAL (run once by a developer; the
# tests read only the committed files and need no GDAL: apt-get install -y gdal-bin):
#   sh scripts/make_webtile_fixtures.sh
# The tiles: gdal2tiles cuts the Blue Marble image of tests/fixtures/imagery/ (EPSG:4326 by its
# world file) into the XYZ pyramid of Web Mercator at zooms 3 to 7. The ground points: GDAL reads
# the tiles back as one raster per zoom (its WMS driver over the tile folder) and gives the
# colour and the global pixel at each point, and the source image's colour there.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
source="$here/tests/fixtures/imagery/bmng_himalaya_4arcmin.jpg"
out="$here/tests/fixtures/webtiles"
tiles="$out/bmng"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

rm -rf "$tiles"
# -s: the world file names no CRS; -r average: GDAL's default, said here so it stays; one
# process so the output does not depend on the machine; no viewer pages.
gdal2tiles.py --xyz -z 3-7 -s EPSG:4326 -r average -w none --processes=1 -q "$source" "$tiles"

# The tiles of one zoom as one raster: the whole Web Mercator square, 256 * 2^z pixels a side.
wms() {
  cat > "$tmp/z$1.xml" <<XML
<GDAL_WMS>
  <Service name="TMS"><ServerUrl>file://$tiles/\${z}/\${x}/\${y}.png</ServerUrl></Service>
  <DataWindow>
    <UpperLeftX>-20037508.342789244</UpperLeftX><UpperLeftY>20037508.342789244</UpperLeftY>
    <LowerRightX>20037508.342789244</LowerRightX><LowerRightY>-20037508.342789244</LowerRightY>
    <TileLevel>$1</TileLevel><TileCountX>1</TileCountX><TileCountY>1</TileCountY><YOrigin>top</YOrigin>
  </DataWindow>
  <Projection>EPSG:3857</Projection><BlockSizeX>256</BlockSizeX><BlockSizeY>256</BlockSizeY><BandsCount>4</BandsCount>
  <ZeroBlockHttpCodes>204,404</ZeroBlockHttpCodes><ZeroBlockOnServerException>true</ZeroBlockOnServerException>
</GDAL_WMS>
XML
}

# "pixel line r g b a" of a point (lon, lat) in a raster.
at() {
  gdallocationinfo -xml "$@" | tr -d '\n' | sed -E 's/.*pixel="([0-9]+)" line="([0-9]+)".*/\1 \2 /;' > "$tmp/loc"
  gdallocationinfo -valonly "$@" | tr '\n' ' ' >> "$tmp/loc"
  cat "$tmp/loc"
}

# Ground points of tests/fixtures/imagery/README.md (interior of the image; lon, lat).
points="Bay_of_Bengal 89.5 21.0333
Siling_Co 89.1 31.8333
Taklamakan_south_edge 81.9667 37.7
Khumbu_snow 86.9667 28.1
Ganges_plain 84.9667 25.6333"

{
  echo '{'
  echo '  "source": "bmng_himalaya_4arcmin.jpg",'
  echo '  "tileZooms": [3, 7],'
  echo '  "points": ['
  first=1
  echo "$points" | while read -r name lon lat; do
    [ $first -eq 1 ] || echo ','
    first=0
    set -- $(at -geoloc "$source" "$lon" "$lat")
    src="[$3, $4, $5]"
    printf '    { "name": "%s", "lon": %s, "lat": %s, "source": %s' "$(echo "$name" | tr '_' ' ')" "$lon" "$lat" "$src"
    for z in 4 7; do
      wms $z
      set -- $(at -wgs84 "$tmp/z$z.xml" "$lon" "$lat")
      printf ',\n      "z%s": { "pixel": [%s, %s], "rgba": [%s, %s, %s, %s] }' "$z" "$1" "$2" "$3" "$4" "$5" "$6"
    done
    printf ' }'
  done
  echo
  echo '  ]'
  echo '}'
} > "$out/bmng_points.json"
echo "wrote $(find "$tiles" -name '*.png' | wc -l) tiles ($(du -sb "$tiles" | cut -f1) bytes) and $out/bmng_points.json"
