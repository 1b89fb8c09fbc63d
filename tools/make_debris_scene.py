#!/usr/bin/python3
"""Builds the example two-phase scene data/kot_debrisflow/ (a debris flow from a real release area).

Same terrain crop as data/kot_dambreak (AvaFrame's avaKot, see data/ATTRIBUTION.md): the DEM is
copied from data/kot_dambreak/dem.tif, and the release is AvaFrame's avaKot release area (relKot,
1.0 m thick in AvaFrame) cropped to the same window. The released mixture is saturated debris:
solid fraction alpha_s = 0.6 of the release thickness as solids, the rest as water.

Usage (Debian's python3 with python3-numpy and python3-gdal):
    /usr/bin/python3 tools/make_debris_scene.py [RELEASE.tif]
Default release: ../shared/data/terrain/avaKot/release.tif relative to the repository root.
"""

import os
import sys

import numpy as np
from osgeo import gdal

gdal.UseExceptions()
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WINDOW = (191, 100, 250, 200)  # the crop of tools/make_example_scene.py (row0, col0, rows, cols)
ALPHA_S = 0.6
OPTIONS = ["COMPRESS=DEFLATE", "PREDICTOR=3", "ZLEVEL=9", "TILED=YES"]

RUN_FILE = """[Talus run file]
# Two-phase debris flow from the avaKot release area (tools/make_debris_scene.py).
[Input]
Map Directory=.
DEM=../kot_dambreak/dem.tif
Include Initial Water=1
Initial Fluid Height=fluid.tif
[Solids]
Include Initial Solids=1
Initial Solid Height=solids.tif
Initial Solid Density=2650
Initial Solid IFA=0.6
Initial Solid Rocksize=0.05
Earth Pressure=savage-hutter
Drag Law=linear
[Flow]
Manning=0.05
[Time]
End Time=2
Timestep=20
[Numerics]
Precision=float
Limiter=minmod
[Output]
Output Directory=output
"""


def main():
    release_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        REPO, "..", "shared", "data", "terrain", "avaKot", "release.tif")
    dem = gdal.Open(os.path.join(REPO, "data", "kot_dambreak", "dem.tif"))
    rel = gdal.Open(release_path)
    r0, c0, nr, nc = WINDOW
    thickness = rel.GetRasterBand(1).ReadAsArray(c0, r0, nc, nr).astype(np.float64)
    thickness[~np.isfinite(thickness)] = 0.0
    thickness[thickness < 0] = 0.0
    out = os.path.join(REPO, "data", "kot_debrisflow")
    os.makedirs(out, exist_ok=True)
    for name, frac in (("solids.tif", ALPHA_S), ("fluid.tif", 1.0 - ALPHA_S)):
        d = gdal.GetDriverByName("GTiff").Create(os.path.join(out, name), nc, nr, 1, gdal.GDT_Float32, OPTIONS)
        d.SetGeoTransform(dem.GetGeoTransform())
        d.SetProjection(dem.GetProjection())
        d.GetRasterBand(1).WriteArray((thickness * frac).astype(np.float32))
        d = None
    with open(os.path.join(out, "kot_debrisflow.run"), "w") as f:
        f.write(RUN_FILE)
    dx = dem.GetGeoTransform()[1]
    print("release cells %d, volume %.1f m3 (solids %.1f, water %.1f)" % (
        (thickness > 0).sum(), thickness.sum() * dx * dx, ALPHA_S * thickness.sum() * dx * dx,
        (1 - ALPHA_S) * thickness.sum() * dx * dx))


if __name__ == "__main__":
    main()
