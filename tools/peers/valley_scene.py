#!/usr/bin/env python3
"""A curved valley at an angle to the grid, as rasters for Talus and com1DFA (issue 13, items 1, 5).

  valley_scene.py OUT_DIR [--angle-deg 30]

The scene of tests/verification/test_oblique_valley.cpp: a 1D profile b(s) along the direction s at
ANGLE to the grid's x axis, a 40 deg slope turning into a flat floor over W = 100 m (b' linear in s
there, tests/support/ValleyBead.hpp), 5 m cells, a disc release of radius 34 m with its centroid
400 m above the floor. Writes OUT_DIR/dem.tif, release.tif (slope-normal thickness 1.5 m, what
com1DFA reads), solids_vertical.tif (h_n / cos(theta), what Talus reads; same volume), along.tif (s
of each cell centre, for terrain_centroid.py) and case.run (Talus: dry granular, Coulomb
delta = 25 deg, K = 1, cos^4: terrain_compare.py's solids_runfile, as for the terrain cases).
Run both codes on it with
    talus run case.run --out out --precision double --set "Stop At Rest Fraction=0.01"
    /work/avaframe-venv/bin/python tools/peers/terrain_avaframe_run.py OUT_DIR WORK_DIR
and compare with terrain_centroid.py valley. The bead (exact, with the bend's centripetal friction)
travels 690.4 m from the release centroid; the energy line without it 857.8 m.

Run with a python that has numpy and rasterio (e.g. the AvaFrame virtual environment's).
"""
import argparse
import pathlib
import sys

import numpy as np
import rasterio
from rasterio.crs import CRS
from rasterio.transform import from_origin

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from terrain_compare import slope_cos, solids_runfile  # noqa: E402

ALPHA1, W, Z0, MARGIN = 40.0, 100.0, 400.0, 100.0
DX, LENGTH, HALF_WIDTH, RADIUS, H_NORMAL = 5.0, 1050.0, 200.0, 34.0, 1.5


def bed(s):
    """b(s), 0 on the floor: slope -s1 until xa, b' linear to 0 over W, flat beyond."""
    s1 = np.tan(np.radians(ALPHA1))
    xa = Z0 / s1 + MARGIN
    prim = np.where(s <= xa, -s1 * (s - xa),
                    np.where(s <= xa + W, -s1 * (s - xa) + 0.5 * s1 * (s - xa) ** 2 / W, -0.5 * s1 * W))
    return prim + 0.5 * s1 * W, xa


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--angle-deg", type=float, default=30.0)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    phi = np.radians(a.angle_deg)
    c, sn = np.cos(phi), np.sin(phi)
    es, ec = np.array([0, LENGTH, 0, LENGTH]), np.array([-HALF_WIDTH, -HALF_WIDTH, HALF_WIDTH, HALF_WIDTH])
    px, py = es * c - ec * sn, es * sn + ec * c
    nx = int(np.ceil((px.max() - px.min()) / DX))
    ny = int(np.ceil((py.max() - py.min()) / DX))
    x = px.min() + (np.arange(nx) + 0.5) * DX
    y = py.max() - (np.arange(ny) + 0.5) * DX  # row 0 is the northern edge
    X, Y = np.meshgrid(x, y)
    S, C = X * c + Y * sn, -X * sn + Y * c
    b, xa = bed(np.maximum(S, -300.0))
    s1 = np.tan(np.radians(ALPHA1))
    s_release = xa - (Z0 - 0.5 * s1 * W) / s1  # where the straight slope is Z0 above the floor
    dem = b + 100.0
    hn = np.where(np.hypot(S - s_release, C) < RADIUS, H_NORMAL, 0.0)
    cos = slope_cos(dem, DX)
    crs = CRS.from_epsg(31287)  # any metric CRS; com1DFA wants one
    tr = from_origin(600000.0 + px.min(), 5200000.0 + py.max(), DX, DX)
    for name, arr in (("dem", dem), ("release", hn), ("solids_vertical", hn / cos), ("along", S)):
        with rasterio.open(a.out / f"{name}.tif", "w", driver="GTiff", height=ny, width=nx, count=1,
                           dtype="float64", crs=crs, transform=tr, nodata=-9999.0) as ds:
            ds.write(arr, 1)
    (a.out / "case.run").write_text(solids_runfile(
        f"# Curved valley at {a.angle_deg:g} deg to the grid (tools/peers/valley_scene.py).", "dem.tif",
        np.radians(25.0), tend_s=150.0, report_s=10.0))
    print(f"{a.out}: {nx} x {ny} cells, release volume {float((hn / cos).sum()) * DX * DX:.0f} m3")


if __name__ == "__main__":
    main()
