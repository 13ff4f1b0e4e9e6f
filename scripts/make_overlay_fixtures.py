#!/usr/bin/python3
"""Makes tests/fixtures/overlays/: GPX, KML, KMZ and GeoJSON files over the real Everest DEM of
tests/fixtures/measure/everest_utm45.tif (EPSG:32645), and expected.json, with GDAL (python3-gdal):
the track's vertices carried to UTM 45N and to the DEM's pixels by OSR, and the DEM's heights
under them read with GDAL, for the tests to check the product against. Run once; the outputs
are committed (the product and its tests never need GDAL).

    /usr/bin/python3 scripts/make_overlay_fixtures.py
"""
import io, json, math, os, random, zipfile
from osgeo import gdal, osr

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, '..', 'tests', 'fixtures', 'overlays')
DEM = os.path.join(HERE, '..', 'tests', 'fixtures', 'measure', 'everest_utm45.tif')
random.seed(7)

dataset = gdal.Open(DEM)
band = dataset.GetRasterBand(1)
heights = band.ReadAsArray().astype(float)
gt = dataset.GetGeoTransform()
wgs84 = osr.SpatialReference(); wgs84.ImportFromEPSG(4326); wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
utm = osr.SpatialReference(); utm.ImportFromEPSG(32645); utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
to_utm = osr.CoordinateTransformation(wgs84, utm)
to_lonlat = osr.CoordinateTransformation(utm, wgs84)

def pixel(lon, lat):
    """(column, row) of a point, sample centres at integers (the DEM's first sample is 0, 0)."""
    x, y, _ = to_utm.TransformPoint(lon, lat)
    return x, y, (x - gt[0]) / gt[1] - 0.5, (y - gt[3]) / gt[5] - 0.5

NODATA = band.GetNoDataValue()

def dem_height(lon, lat):
    """Bilinear between the four samples around the point, over the valid ones (the DEM has voids)."""
    _, _, c, r = pixel(lon, lat)
    i, j = int(math.floor(c)), int(math.floor(r))
    fu, fv = c - i, r - j
    total = weight = 0.0
    for dj, di, w in ((0, 0, (1 - fu) * (1 - fv)), (0, 1, fu * (1 - fv)), (1, 0, (1 - fu) * fv), (1, 1, fu * fv)):
        h = heights[j + dj, i + di]
        if h != NODATA and h > -1000:
            total += h * w; weight += w
    return total / weight if weight > 0 else float('nan')

# The Everest Base Camp trek: Lukla, Namche Bazaar, Tengboche, Dingboche, Lobuche, Gorak Shep, the base camp.
TREK = [(86.7314, 27.6866), (86.7200, 27.7400), (86.7138, 27.8043), (86.7642, 27.8361), (86.8306, 27.8923),
        (86.8103, 27.9483), (86.8286, 27.9800), (86.8528, 28.0026)]
PLACES = [('Lukla', 86.7314, 27.6866), ('Namche Bazaar', 86.7138, 27.8043), ('Tengboche', 86.7642, 27.8361),
          ('Everest Base Camp', 86.8528, 28.0026)]
PEAKS = [('Mount Everest', 86.9250, 27.9881, 8849), ('Lhotse', 86.9336, 27.9617, 8516), ('Makalu', 87.0888, 27.8897, 8485),
         ('Cho Oyu', 86.6608, 28.0942, 8188), ('Ama Dablam', 86.8614, 27.8614, 6812)]

def densify(points, count):
    lengths = [math.dist(a, b) for a, b in zip(points, points[1:])]
    total, out = sum(lengths), []
    for k in range(count):
        d, i = total * k / (count - 1), 0
        while i < len(lengths) - 1 and d > lengths[i]:
            d -= lengths[i]; i += 1
        s = min(1.0, d / lengths[i])
        a, b = points[i], points[i + 1]
        # A walker's wander, tens of metres across the path.
        wob = 0.0004 * math.sin(k * 0.7) if 0 < k < count - 1 else 0
        out.append((a[0] + (b[0] - a[0]) * s + wob, a[1] + (b[1] - a[1]) * s - wob))
    return out

track = densify(TREK, 400)
start = 1748761200  # 2025-06-01T07:00:00Z
def iso(t): return __import__('datetime').datetime.utcfromtimestamp(t).strftime('%Y-%m-%dT%H:%M:%SZ')
trkpts, expected_vertices, t, last_ele = [], [], start, 0.0
for k, (lon, lat) in enumerate(track):
    ground = dem_height(lon, lat)
    ele = (ground if ground == ground else last_ele) + random.uniform(-6, 6)
    last_ele = ele
    if k: t += 90 + (600 if k == 200 else 0)  # a long stop at Dingboche's tea house
    trkpts.append(f'      <trkpt lat="{lat:.7f}" lon="{lon:.7f}"><ele>{ele:.1f}</ele><time>{iso(t)}</time></trkpt>')
    if k % 40 == 0 or k == len(track) - 1:
        x, y, c, r = pixel(lon, lat)
        expected_vertices.append({'vertex': k, 'lon': round(lon, 7), 'lat': round(lat, 7), 'easting': x, 'northing': y,
                                  'column': c, 'row': r, 'dem_height': dem_height(lon, lat) if dem_height(lon, lat) == dem_height(lon, lat) else None})
wpts = '\n'.join(f'  <wpt lat="{lat}" lon="{lon}"><ele>{dem_height(lon, lat):.0f}</ele><name>{name}</name></wpt>' for name, lon, lat in PLACES)
rte = '\n'.join(f'    <rtept lat="{lat}" lon="{lon}"/>' for lon, lat in [(86.8286, 27.9800), (86.8286, 27.9958)])
gpx11 = f'''<?xml version="1.0" encoding="UTF-8"?>
<gpx version="1.1" creator="hexlod make_overlay_fixtures.py" xmlns="http://www.topografix.com/GPX/1/1">
{wpts}
  <rte><name>Kala Patthar</name>
{rte}
  </rte>
  <trk><name>Everest Base Camp trek</name>
    <trkseg>
{chr(10).join(trkpts)}
    </trkseg>
  </trk>
</gpx>
'''
gpx10 = f'''<?xml version="1.0"?>
<gpx version="1.0" creator="hexlod" xmlns="http://www.topografix.com/GPX/1/0">
  <trk><name>Gokyo approach</name><trkseg>
{chr(10).join(f'    <trkpt lat="{lat:.6f}" lon="{lon:.6f}"><ele>{dem_height(lon, lat):.1f}</ele></trkpt>' for lon, lat in densify([(86.7138, 27.8043), (86.6950, 27.9500), (86.6833, 27.9533)], 60))}
  </trkseg></trk>
</gpx>
'''
def kml_coords(points, alt=None): return ' '.join(f'{lon},{lat}' + (f',{alt}' if alt is not None else '') for lon, lat in points)
peaks = '\n'.join(f'''    <Placemark><name>{name}</name><description>{h} m</description>
      <Point><coordinates>{lon},{lat},{h}</coordinates></Point></Placemark>''' for name, lon, lat, h in PEAKS)
kml = f'''<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2">
  <Document><name>Everest places</name>
  <Folder><name>Peaks</name>
{peaks}
  </Folder>
    <Placemark><name>Khumbu valley trail</name>
      <LineString><altitudeMode>clampToGround</altitudeMode><coordinates>{kml_coords(densify(TREK[3:], 80))}</coordinates></LineString></Placemark>
    <Placemark><name>Flight to Everest</name>
      <LineString><altitudeMode>absolute</altitudeMode><coordinates>{kml_coords(densify([(86.7314, 27.6866), (86.9250, 27.9881)], 30), 9500)}</coordinates></LineString></Placemark>
    <Placemark><name>Base camp area</name>
      <Polygon><outerBoundaryIs><LinearRing><coordinates>{kml_coords([(86.835, 27.990), (86.875, 27.990), (86.875, 28.015), (86.835, 28.015), (86.835, 27.990)])}</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>
    <Placemark><name>Gokyo</name>
      <MultiGeometry><Point><coordinates>86.6833,27.9533</coordinates></Point>
        <LineString><coordinates>{kml_coords([(86.6833, 27.9533), (86.6950, 27.9500)])}</coordinates></LineString></MultiGeometry></Placemark>
  </Document>
</kml>
'''
def feature(geometry, **properties): return {'type': 'Feature', 'properties': properties, 'geometry': geometry}
ring = [[86.80, 27.85], [86.90, 27.85], [86.90, 27.93], [86.80, 27.93], [86.80, 27.85]]
hole = [[86.84, 27.88], [86.86, 27.88], [86.86, 27.90], [86.84, 27.90], [86.84, 27.88]]
geojson = {'type': 'FeatureCollection', 'features': [
    feature({'type': 'Point', 'coordinates': [86.9250, 27.9881, 8849]}, name='Mount Everest', height_m=8849, first_ascent=1953),
    feature({'type': 'MultiPoint', 'coordinates': [[86.9336, 27.9617], [87.0888, 27.8897]]}, name='Lhotse and Makalu'),
    feature({'type': 'LineString', 'coordinates': [[lon, lat] for lon, lat in densify(TREK[:4], 60)]}, name='Lukla to Tengboche', grade='moderate'),
    feature({'type': 'MultiLineString', 'coordinates': [[[86.70, 27.70], [86.75, 27.75]], [[86.95, 27.80], [87.00, 27.85]]]}, name='two paths'),
    feature({'type': 'Polygon', 'coordinates': [ring, hole]}, name='Sagarmatha core', note='with a hole'),
    feature({'type': 'MultiPolygon', 'coordinates': [[[[87.00, 27.60], [87.05, 27.60], [87.05, 27.65], [87.00, 27.60]]], [[[87.10, 27.60], [87.15, 27.60], [87.15, 27.65], [87.10, 27.60]]]]}, name='two fields'),
    feature({'type': 'GeometryCollection', 'geometries': [{'type': 'Point', 'coordinates': [86.8614, 27.8614]}, {'type': 'LineString', 'coordinates': [[86.8614, 27.8614], [86.85, 27.85]]}]}, name='Ama Dablam'),
]}
legacy_line = [to_utm.TransformPoint(lon, lat)[:2] for lon, lat in densify(TREK[:3], 20)]
legacy = {'type': 'FeatureCollection', 'crs': {'type': 'name', 'properties': {'name': 'urn:ogc:def:crs:EPSG::32645'}},
          'features': [feature({'type': 'LineString', 'coordinates': [[round(x, 2), round(y, 2)] for x, y in legacy_line]}, name='Lukla to Namche in UTM')]}
projected = {'type': 'FeatureCollection', 'features': [feature({'type': 'LineString', 'coordinates': [[round(x, 2), round(y, 2)] for x, y in legacy_line]}, name='UTM without crs')]}
alps = '\n'.join(f'      <trkpt lat="{45.83 + k * 0.001:.4f}" lon="{6.86 + k * 0.001:.4f}"><ele>{2000 + k}</ele></trkpt>' for k in range(20))

def write(name, text, mode='w'):
    with open(os.path.join(OUT, name), mode) as f: f.write(text)

os.makedirs(OUT, exist_ok=True)
write('everest_trek.gpx', gpx11)
write('gokyo_gpx10.gpx', gpx10)
write('everest_places.kml', kml)
buffer = io.BytesIO()
with zipfile.ZipFile(buffer, 'w', zipfile.ZIP_DEFLATED) as z: z.writestr('doc.kml', kml)
write('everest_places.kmz', buffer.getvalue(), 'wb')
write('everest_features.geojson', json.dumps(geojson, indent=1))
write('legacy_crs_utm45.geojson', json.dumps(legacy, indent=1))
# Faults.
write('bad_malformed.gpx', gpx11[:len(gpx11) // 2])
write('bad_malformed.geojson', json.dumps(geojson)[:500])
buffer = io.BytesIO()
with zipfile.ZipFile(buffer, 'w') as z: z.writestr('readme.txt', 'no KML here\n'); z.writestr('images/icon.png', b'\x89PNG')
write('bad_no_kml.kmz', buffer.getvalue(), 'wb')
write('bad_empty.gpx', '')
write('bad_projected.geojson', json.dumps(projected, indent=1))
write('off_terrain_alps.gpx', f'<?xml version="1.0"?>\n<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><name>Mont Blanc</name><trkseg>\n{alps}\n</trkseg></trk></gpx>\n')
write('expected.json', json.dumps({
    'dem': {'file': '../measure/everest_utm45.tif', 'crs': 'EPSG:32645', 'geotransform': gt, 'width': dataset.RasterXSize, 'height': dataset.RasterYSize},
    'track': {'file': 'everest_trek.gpx', 'points': len(track), 'vertices': expected_vertices},
    'legacy': {'file': 'legacy_crs_utm45.geojson', 'first_lonlat': list(to_lonlat.TransformPoint(*legacy_line[0])[:2])},
    'made_with': f'GDAL {gdal.__version__} (python3-gdal)',
}, indent=1))
print('wrote', sorted(os.listdir(OUT)))
