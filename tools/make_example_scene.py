#!/usr/bin/python3
"""Builds the example scene data/kot_dambreak/ (a dam break over real terrain).

The DEM is a crop of AvaFrame's avaKot terrain (see data/kot_dambreak/README.md for
provenance and licence). A cylindrical water column is placed on the centroid of the
avaKot release area; its free surface is flat at (highest bed in the disc + 5 m), so the
thickness is h = max(0, level - z) inside the disc and 0 outside. It is released at t = 0.

Usage (Debian's python3 with python3-numpy and python3-gdal):
    /usr/bin/python3 tools/make_example_scene.py [DEM.tif] [--release RELEASE.tif] [--out DIR]
        [--window ROW0 COL0 ROWS COLS] [--name RUNFILE]

Defaults: DEM = ../shared/data/terrain/avaKot/dem.tif relative to the repository root,
release = release.tif next to the DEM, out = data/kot_dambreak in the repository.
The crop is in whole cells, so the georeference of every kept cell is unchanged.
"""

import argparse
import math
import os
import sys

import numpy as np
from osgeo import gdal

gdal.UseExceptions()

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Crop window in source cells, counted from the upper-left corner: (row0, col0, rows, cols).
# It ends at the release area's last row (the terrain rises south of it, so water cannot go
# there) and reaches 250 rows (1.25 km) downslope to the valley floor. The columns hold the
# whole path of AvaFrame's reference avalanche from this release area inside those rows
# (4196 of its 4697 cells with peak thickness > 0); 7.4 % of the window is NoData (outside
# the source DEM's mask, in the south-east corner, away from the flow path).
DEFAULT_WINDOW = (191, 100, 250, 200)
RADIUS_M = 40.0        # radius of the water column [m]
FREEBOARD_M = 5.0      # water surface above the highest bed cell in the disc [m]
CREATION_OPTIONS = ["COMPRESS=DEFLATE", "PREDICTOR=3", "ZLEVEL=9", "TILED=YES"]

RUN_FILE = """[Talus run file]
[Input]
Map Directory=.
DEM=dem.tif
Include Initial Water=1
Initial Fluid Height=water.tif
[Flow]
Manning=0.05
[Time]
Start Time=0
End Time=1.5
Timestep=15
[Numerics]
CFL=0.5
Limiter=vanleer
Riemann Solver=hllc
Precision=float
Boundary Type=open
[Output]
Output Directory=output
"""


def write_tif(path, array, geotransform, projection, nodata):
    driver = gdal.GetDriverByName("GTiff")
    rows, cols = array.shape
    ds = driver.Create(path, cols, rows, 1, gdal.GDT_Float32, options=CREATION_OPTIONS)
    ds.SetGeoTransform(geotransform)
    ds.SetProjection(projection)
    band = ds.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    band.WriteArray(array.astype(np.float32))
    band.FlushCache()
    ds = None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dem", nargs="?",
                        default=os.path.join(REPO, "..", "shared", "data", "terrain", "avaKot", "dem.tif"))
    parser.add_argument("--release", help="release thickness map on the DEM grid (default: release.tif beside the DEM)")
    parser.add_argument("--out", default=os.path.join(REPO, "data", "kot_dambreak"))
    parser.add_argument("--window", type=int, nargs=4, metavar=("ROW0", "COL0", "ROWS", "COLS"),
                        default=DEFAULT_WINDOW)
    parser.add_argument("--name", default="kot_dambreak", help="run-file name without .run (default kot_dambreak)")
    args = parser.parse_args()
    release_path = args.release or os.path.join(os.path.dirname(os.path.abspath(args.dem)), "release.tif")

    src = gdal.Open(args.dem)
    gt = src.GetGeoTransform()
    projection = src.GetProjection()
    band = src.GetRasterBand(1)
    nodata = band.GetNoDataValue()
    dem = band.ReadAsArray().astype(np.float64)
    release = gdal.Open(release_path).ReadAsArray().astype(np.float64)
    if release.shape != dem.shape:
        sys.exit("release map and DEM differ in size")
    if gt[2] != 0.0 or gt[4] != 0.0 or abs(gt[1] + gt[5]) > 1e-9 * abs(gt[1]):
        sys.exit("expected a north-up DEM with square cells")
    dx = gt[1]
    valid = np.isfinite(dem) if nodata is None else (dem != nodata) & np.isfinite(dem)

    # Locate the release area and check that the crop holds it.
    rel_rows, rel_cols = np.nonzero(release > 0)
    if rel_rows.size == 0:
        sys.exit("release map has no cell > 0")
    r0, c0, nr, nc = args.window
    if not (0 <= r0 and 0 <= c0 and r0 + nr <= dem.shape[0] and c0 + nc <= dem.shape[1]):
        sys.exit("window outside the DEM")
    if not (r0 <= rel_rows.min() and rel_rows.max() < r0 + nr and c0 <= rel_cols.min() and rel_cols.max() < c0 + nc):
        sys.exit("window does not hold the release area (rows %d-%d, cols %d-%d)"
                 % (rel_rows.min(), rel_rows.max(), rel_cols.min(), rel_cols.max()))

    # Disc centre: the cell centre nearest to the release area's centroid (in source indices).
    cr = int(round(rel_rows.mean()))
    cc = int(round(rel_cols.mean()))

    crop = (slice(r0, r0 + nr), slice(c0, c0 + nc))
    z = dem[crop]
    ok = valid[crop]
    gt_crop = (gt[0] + c0 * gt[1], gt[1], 0.0, gt[3] + r0 * gt[5], 0.0, gt[5])

    rr, cc_grid = np.mgrid[0:nr, 0:nc]
    dist = np.hypot((rr - (cr - r0)) * dx, (cc_grid - (cc - c0)) * dx)
    disc = (dist <= RADIUS_M) & ok
    if not np.all(ok[dist <= RADIUS_M]):
        sys.exit("the water column touches NoData cells")
    level = z[disc].max() + FREEBOARD_M
    h = np.where(disc, np.maximum(0.0, level - z), 0.0)

    os.makedirs(args.out, exist_ok=True)
    z_out = np.where(ok, z, nodata if nodata is not None else -9999.0)
    write_tif(os.path.join(args.out, "dem.tif"), z_out, gt_crop, projection,
              nodata if nodata is not None else -9999.0)
    write_tif(os.path.join(args.out, "water.tif"), h, gt_crop, projection, None)
    with open(os.path.join(args.out, args.name + ".run"), "w") as f:
        f.write(RUN_FILE)

    cx = gt_crop[0] + (cc - c0 + 0.5) * dx
    cy = gt_crop[3] - (cr - r0 + 0.5) * dx
    h32 = h.astype(np.float32).astype(np.float64)
    print("window (source rows, cols): rows %d-%d, cols %d-%d" % (r0, r0 + nr - 1, c0, c0 + nc - 1))
    print("grid: %d cols x %d rows = %d cells, cell %.12g m" % (nc, nr, nc * nr, dx))
    print("valid cells: %d (%.1f %%), NoData: %d" % (ok.sum(), 100.0 * ok.mean(), (~ok).sum()))
    print("origin (upper-left corner): x = %.6f, y = %.6f" % (gt_crop[0], gt_crop[3]))
    print("bed elevation in the crop: %.2f to %.2f m" % (z[ok].min(), z[ok].max()))
    print("water column: centre cell (row %d, col %d) of the crop, x = %.3f, y = %.3f" % (cr - r0, cc - c0, cx, cy))
    print("  radius %.1f m, %d cells, bed %.2f to %.2f m, water surface %.2f m"
          % (RADIUS_M, disc.sum(), z[disc].min(), z[disc].max(), level))
    print("  max depth %.2f m, mean depth %.2f m" % (h32.max(), h32[disc].mean()))
    print("  volume sum(h*dx*dy) = %.1f m3" % (h32.sum() * dx * dx))
    print("wrote %s/{dem.tif,water.tif,%s.run}" % (os.path.relpath(args.out, REPO), args.name))


if __name__ == "__main__":
    main()
