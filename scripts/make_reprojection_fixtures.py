#!/usr/bin/python3
"""Make the reprojection fixtures of tests/fixtures/reprojection/ with GDAL (Debian's
python3-gdal and gdal-bin; fixture time only: the tests never need GDAL).

  * himalaya_utm45_2500m.tif: the default terrain's real DEM (NOAA GLOBE, public/terrain/
    globe_himalaya_2048.png, EPSG:4326) warped by gdalwarp (bilinear) to UTM 45N (EPSG:32645),
    240 x 240 samples of 2500 m (600 km) around Everest, within the source: a UTM DEM.
  * bmng_himalaya_4326.tif: the Blue Marble image of tests/fixtures/imagery (jpg + jgw) as a
    GeoTIFF that names its CRS (EPSG:4326), pixels unchanged.
  * bmng_himalaya_3857.tif: the same warped by gdalwarp (bilinear) to Web Mercator (EPSG:3857).
  * index_on_dem_4326.u16.gz, index_on_dem_3857.u16.gz: where gdalwarp puts each image's pixels
    on the DEM's grid. Each image's pixels are numbered (band 1 = column, band 2 = row) and
    warped with nearest-neighbour and the exact transformer (-et 0) onto the DEM's grid; each DEM sample holds the column and row
    of the image pixel gdalwarp picked for it (little-endian uint16 pairs, row by row; 65535
    where it picked none), gzipped.
  * expected.json: the grids (sample-centre georeferences) and the files.

Usage: /usr/bin/python3 scripts/make_reprojection_fixtures.py
"""
import gzip
import math
import json
import os

import numpy as np
from osgeo import gdal, osr

gdal.UseExceptions()
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
OUT = os.path.join(ROOT, "tests", "fixtures", "reprojection")
DEM_SIZE, DEM_STEP = 240, 2500.0


def georef(ds):
    """Sample-centre georeference of a north-up dataset."""
    x, dx, _, y, _, dy = ds.GetGeoTransform()
    return {"x0": x + dx / 2, "y0": y + dy / 2, "dx": dx, "dy": dy, "width": ds.RasterXSize, "height": ds.RasterYSize}


def srs_wkt(code):
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(code)
    return srs.ExportToWkt()


def everest_utm():
    wgs, utm = osr.SpatialReference(), osr.SpatialReference()
    wgs.ImportFromEPSG(4326)
    utm.ImportFromEPSG(32645)
    wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    # West of Everest, so that the 600 km square stays inside the source DEM (east edge 90 E).
    x, y, _ = osr.CoordinateTransformation(wgs, utm).TransformPoint(86.5, 27.9881)
    return round(x / DEM_STEP) * DEM_STEP, round(y / DEM_STEP) * DEM_STEP


def ground_points(img4326, img3857, bounds, wanted=5):
    """Ground points inside the DEM at pixel centres of the EPSG:4326 image whose 5 x 5
    neighbourhood is one colour (within 10 a channel, so that a texel off shows no difference),
    spread apart: lon, lat, UTM x, y and each image's colour there (its pixel's, nearest)."""
    wgs, utm, merc = (osr.SpatialReference() for _ in range(3))
    for srs, code in ((wgs, 4326), (utm, 32645), (merc, 3857)):
        srs.ImportFromEPSG(code)
        srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_utm, to_merc = osr.CoordinateTransformation(wgs, utm), osr.CoordinateTransformation(wgs, merc)
    rgb4326 = np.stack([img4326.GetRasterBand(b).ReadAsArray() for b in (1, 2, 3)], axis=-1).astype(int)
    rgb3857 = np.stack([img3857.GetRasterBand(b).ReadAsArray() for b in (1, 2, 3)], axis=-1).astype(int)
    x0, dx, _, y0, _, dy = img4326.GetGeoTransform()
    mx0, mdx, _, my0, _, mdy = img3857.GetGeoTransform()
    points = []
    for j in range(3, rgb4326.shape[0] - 3):
        for i in range(3, rgb4326.shape[1] - 3):
            lon, lat = x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy
            x, y, _ = to_utm.TransformPoint(lon, lat)
            if not (bounds[0] + 20000 < x < bounds[2] - 20000 and bounds[1] + 20000 < y < bounds[3] - 20000):
                continue
            patch = rgb4326[j - 2:j + 3, i - 2:i + 3]
            if np.abs(patch - rgb4326[j, i]).max() > 10:
                continue
            if any(math.hypot(x - p["x"], y - p["y"]) < 120000 for p in points):
                continue
            mx, my, _ = to_merc.TransformPoint(lon, lat)
            mi, mj = int((mx - mx0) // mdx), int((my - my0) // mdy)
            points.append({"lon": lon, "lat": lat, "x": x, "y": y, "rgb4326": rgb4326[j, i].tolist(), "rgb3857": rgb3857[mj, mi].tolist()})
            if len(points) == wanted:
                return points
    return points


def main():
    os.makedirs(OUT, exist_ok=True)
    # The 16-bit PNG holds h = min + v / 65535 * (max - min), min and max in its .json.
    png = os.path.join(ROOT, "public", "terrain", "globe_himalaya_2048.png")
    meta = json.load(open(png.replace(".png", ".json")))
    png_ds = gdal.Open(png)  # kept: a band outlives no dataset in GDAL's Python
    v = png_ds.GetRasterBand(1).ReadAsArray().astype(np.float32)
    heights = meta["min"] + v / 65535 * (meta["max"] - meta["min"])
    src = gdal.GetDriverByName("MEM").Create("", 2048, 2048, 1, gdal.GDT_Float32)
    src.SetGeoTransform((72.93333333333334, 1 / 120, 0, 37.916666666666664, 0, -1 / 120))
    src.SetProjection(srs_wkt(4326))
    src.GetRasterBand(1).WriteArray(heights)
    cx, cy = everest_utm()
    half = DEM_SIZE * DEM_STEP / 2
    bounds = (cx - half, cy - half, cx + half, cy + half)
    dem_path = os.path.join(OUT, "himalaya_utm45_2500m.tif")
    dem = gdal.Warp(dem_path, src, dstSRS="EPSG:32645", outputBounds=bounds, xRes=DEM_STEP, yRes=DEM_STEP,
                    resampleAlg="bilinear", outputType=gdal.GDT_Int16, creationOptions=["COMPRESS=DEFLATE", "PREDICTOR=2"])

    jpg = os.path.join(ROOT, "tests", "fixtures", "imagery", "bmng_himalaya_4arcmin.jpg")
    img4326 = gdal.Translate(os.path.join(OUT, "bmng_himalaya_4326.tif"), jpg, outputSRS="EPSG:4326",
                             creationOptions=["COMPRESS=DEFLATE", "PREDICTOR=2"])
    img3857 = gdal.Warp(os.path.join(OUT, "bmng_himalaya_3857.tif"), img4326, dstSRS="EPSG:3857", resampleAlg="bilinear",
                        creationOptions=["COMPRESS=DEFLATE", "PREDICTOR=2"])

    for ds in (dem, img4326, img3857):
        ds.FlushCache()  # written before the interpreter ends (GDAL's Python datasets flush on close)
    expected = {"dem": {"file": os.path.basename(dem_path), "crs": "EPSG:32645", **georef(dem)}, "images": {}}
    for code, image in (("4326", img4326), ("3857", img3857)):
        w, h = image.RasterXSize, image.RasterYSize
        index = gdal.GetDriverByName("MEM").Create("", w, h, 2, gdal.GDT_UInt16)
        index.SetGeoTransform(image.GetGeoTransform())
        index.SetProjection(image.GetProjection())
        columns, rows = np.meshgrid(np.arange(w, dtype=np.uint16), np.arange(h, dtype=np.uint16))
        index.GetRasterBand(1).WriteArray(columns)
        index.GetRasterBand(2).WriteArray(rows)
        for b in (1, 2):
            index.GetRasterBand(b).SetNoDataValue(65535)
        on_dem = gdal.Warp("", index, format="MEM", dstSRS="EPSG:32645", outputBounds=bounds, xRes=DEM_STEP, yRes=DEM_STEP,
                           resampleAlg="near", dstNodata=65535,
                           errorThreshold=0)  # the exact transformer: where PROJ puts each sample, not an approximation
        pairs = np.stack([on_dem.GetRasterBand(1).ReadAsArray(), on_dem.GetRasterBand(2).ReadAsArray()], axis=-1).astype("<u2")
        name = f"index_on_dem_{code}.u16.gz"
        with gzip.GzipFile(os.path.join(OUT, name), "wb", mtime=0) as f:
            f.write(pairs.tobytes())
        expected["images"][code] = {"file": f"bmng_himalaya_{code}.tif", "index": name, "crs": f"EPSG:{code}", **georef(image)}
    expected["points"] = ground_points(img4326, img3857, bounds)
    with open(os.path.join(OUT, "expected.json"), "w") as f:
        json.dump(expected, f, indent=1)
        f.write("\n")


main()
