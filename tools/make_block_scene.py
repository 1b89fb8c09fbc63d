#!/usr/bin/python3
"""Builds the example hybrid-mode scene data/block_slide/: the paper's numerical test, setup 1
(OpenLISEM Hazard 2.0a, section 3; geometry as reconstructed in ../shared/spec/model.md section 11):
a 30-degree planar slope 600 m long running into a flat plain, and a block of 100 m x 100 m x 20 m
released near the top, alpha_s = 0.5 (10 m of solids and 10 m of water per cell), all of it structured
(f_sc = f_fc = 1), so the whole block becomes particles. Cell size 10 m, as in the paper.

The run-file uses the strong material of scenario A (c = 500 kPa: the block should slide as one piece)
with a bed friction angle of 20 degrees and E = 100 MPa (the paper's 10^12 Pa would make the
particle step 100 times shorter for the same result at this resolution; see docs/particles.md).

Usage (Debian's python3 with python3-numpy and python3-gdal):
    /usr/bin/python3 tools/make_block_scene.py [OUTPUT_DIR]
"""

import math
import os
import sys

import numpy as np
from osgeo import gdal, osr

gdal.UseExceptions()
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DX = 10.0
NX, NY = 100, 30            # 1000 m along the slope direction, 300 m across
SLOPE_CELLS = 60            # 600 m of 30-degree slope, then the plain
BLOCK = (5, 15, 10, 20)     # columns 5..14, rows 10..19: 100 m x 100 m
THICKNESS, ALPHA_S = 20.0, 0.5
OPTIONS = ["COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=YES"]

RUN_FILE = """[Talus run file]
# OpenLISEM Hazard 2.0a numerical test, setup 1, scenario A (tools/make_block_scene.py).
[Input]
Map Directory=.
DEM=dem.tif
Include Initial Water=1
Initial Fluid Height=fluid.tif
[Solids]
Include Initial Solids=1
Initial Solid Height=solids.tif
Initial Solid Density=2400
Initial Solid IFA=0.349
Initial Cohesion=500
Earth Pressure=constant
Earth Pressure Coefficient=1
[Particles]
Use Material Point Method=1
Young Modulus=1e8
Poisson Ratio=0.3
Particles Per Cell=4
[Time]
End Time=1
Timestep=10
[Numerics]
Precision=float
[Output]
Output Directory=output
"""


def write(path, array, template=None):
    drv = gdal.GetDriverByName("GTiff")
    ds = drv.Create(path, NX, NY, 1, gdal.GDT_Float32, OPTIONS)
    # A local metric frame (UTM 32N numbers, origin at an arbitrary point); rows run north to south.
    ds.SetGeoTransform((600000.0, DX, 0.0, 5200000.0 + NY * DX, 0.0, -DX))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32632)
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(array.astype(np.float32))
    ds = None


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO, "data", "block_slide")
    os.makedirs(out, exist_ok=True)
    x = (np.arange(NX) + 0.5) * DX
    drop = math.tan(math.radians(30.0)) * SLOPE_CELLS * DX
    z = np.where(x < SLOPE_CELLS * DX, drop - math.tan(math.radians(30.0)) * x, 0.0)
    dem = np.tile(z, (NY, 1))
    solids = np.zeros((NY, NX))
    c0, c1, r0, r1 = BLOCK
    solids[r0:r1, c0:c1] = ALPHA_S * THICKNESS
    fluid = np.zeros((NY, NX))
    fluid[r0:r1, c0:c1] = (1 - ALPHA_S) * THICKNESS
    write(os.path.join(out, "dem.tif"), dem)
    write(os.path.join(out, "solids.tif"), solids)
    write(os.path.join(out, "fluid.tif"), fluid)
    with open(os.path.join(out, "block_slide.run"), "w") as f:
        f.write(RUN_FILE)
    print("wrote", out)


if __name__ == "__main__":
    main()
