#!/usr/bin/env python3
"""Grid convergence of a Coulomb flow that partly leaves a channel at a bend (issue 13, item 5).

  bend_convergence.py WORK_DIR [--talus build/src/talus] [--cells 10,5,2.5,1.25] [--rough 1]

Run with a python that has numpy and GDAL (Debian's python3-gdal, or a venv with it). An analytic
terrain, so every cell size sees the same surface (no resampled DEM): a 35-degree hillside falling
to the south (-y) that flattens over 40 m around 450 m below the top, with a Gaussian channel (depth
D = 15 m, width W = 15 m) running down the fall line for 150 m and then turning by 30 degrees to the
east on an arc of radius 100 m, across the hillside. With --rough A the surface gets 24 plane
sinusoids of wavelength 8-40 m (fixed seed, amplitude about A/sqrt(12) each times lambda/40), the
same at every cell size. Release: a parabolic cap, 3 m thick, 24 m x 60 m, in the channel below the
top. Coulomb friction 25 degrees, K = 1, cos^4, curvature on, 90 s (the run-file of
tools/peers/terrain_compare.py's avaKot comparison). Output per cell size: the area with peak
thickness > 0.1 m, the share of the final volume more than 25 m from the channel axis (the spill),
the mean position of the spilled and of the channelled deposit, and the peak speed. A flow that
converges has a spill share that settles as the cells shrink.
"""
import argparse
import os
import pathlib
import subprocess
import sys

import numpy as np
from osgeo import gdal

gdal.UseExceptions()
TAN35 = np.tan(np.radians(35.0))
D, W, TURN, R = 15.0, 15.0, np.radians(30.0), 100.0
BOX = (-150.0, 450.0, -700.0, 60.0)  # x0, x1, y0, y1 [m]
RUN = """[Talus run file]
# tools/validation/bend_convergence.py: analytic hillside with a bending channel.
[Input]
Map Directory=.
DEM=dem.tif
Include Initial Water=0
[Solids]
Include Initial Solids=1
Initial Solid Height=release.tif
Initial Solid IFA=0.436332
Bed Friction Equals IFA=0
Bed Friction Angle=0.436332
Earth Pressure=constant
Earth Pressure Coefficient=1
Drag Law=off
[Time]
End Time=1.5
Timestep=10
[Flow]
Slope Correction=1
Depth Pressure=cos4
[Numerics]
Precision=double
[Output]
Report Series=0
Output Directory=out
"""


def segment_distance(px, py, ax, ay, bx, by):
    vx, vy = bx - ax, by - ay
    t = np.clip(((px - ax) * vx + (py - ay) * vy) / (vx * vx + vy * vy), 0.0, 1.0)
    return np.hypot(px - ax - t * vx, py - ay - t * vy)


def terrain(dx, rough):
    x0, x1, y0, y1 = BOX
    nc, nr = int(round((x1 - x0) / dx)), int(round((y1 - y0) / dx))
    X, Y = np.meshgrid(x0 + dx * (np.arange(nc) + 0.5), y1 - dx * (np.arange(nr) + 0.5))
    # Channel axis: x = 0 from y = 100 down to y = -150, an arc about (R, -150) turning east, a ray.
    cx, cy = R, -150.0
    ex, ey = cx - R * np.cos(TURN), cy - R * np.sin(TURN)
    tx, ty = np.sin(TURN), -np.cos(TURN)
    d_line = segment_distance(X, Y, 0.0, 100.0, 0.0, -150.0)
    d_ray = segment_distance(X, Y, ex, ey, ex + 2000 * tx, ey + 2000 * ty)
    ang = np.arctan2(-(Y - cy), -(X - cx))
    d_arc = np.where((ang >= 0) & (ang <= TURN), np.abs(np.hypot(X - cx, Y - cy) - R), np.inf)
    dist = np.minimum(np.minimum(d_line, d_arc), d_ray)
    s = -Y
    z = 1000.0 - TAN35 * (s - 40.0 * np.logaddexp(0.0, (s - 450.0) / 40.0)) - D * np.exp(-(dist / W) ** 2)
    if rough > 0:
        rng = np.random.default_rng(7)
        bumps = np.zeros_like(X)
        for _ in range(24):
            lam, th, ph = rng.uniform(8, 40), rng.uniform(0, np.pi), rng.uniform(0, 2 * np.pi)
            bumps += np.sin(2 * np.pi * (X * np.cos(th) + Y * np.sin(th)) / lam + ph) * lam / 40
        z += bumps * rough / np.sqrt(12.0)
    release = 3.0 * np.clip(1 - (X / 12.0) ** 2 - ((Y + 40.0) / 30.0) ** 2, 0.0, None)
    return z, release, dist, X, Y


def write(path, arr, dx):
    ds = gdal.GetDriverByName("GTiff").Create(str(path), arr.shape[1], arr.shape[0], 1, gdal.GDT_Float64)
    ds.SetGeoTransform((BOX[0], dx, 0, BOX[3], 0, -dx))
    ds.GetRasterBand(1).WriteArray(arr)
    ds = None


def read(path):
    a = gdal.Open(str(path)).ReadAsArray().astype(float)
    return np.where(np.isfinite(a), a, 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work", type=pathlib.Path)
    ap.add_argument("--talus", default="build/src/talus")
    ap.add_argument("--cells", default="10,5,2.5,1.25")
    ap.add_argument("--rough", type=float, default=0.0)
    a = ap.parse_args()
    print("| cell [m] | area > 0.1 m [m²] | spill share | spill mean x, y [m] | channel deposit mean y [m] | peak speed [m/s] |")
    print("|---|---|---|---|---|---|")
    for dx in (float(c) for c in a.cells.split(",")):
        d = a.work / f"cell_{dx:g}"
        d.mkdir(parents=True, exist_ok=True)
        z, release, dist, X, Y = terrain(dx, a.rough)
        write(d / "dem.tif", z, dx)
        write(d / "release.tif", release, dx)
        (d / "case.run").write_text(RUN)
        subprocess.run([os.path.abspath(a.talus), "run", "case.run", "--out", "out", "--precision", "double",
                        "--overwrite", "--quiet"], cwd=d, check=True)
        hmax, hfin, vmax = read(d / "out/hsmax.tif"), read(d / "out/hsfinal.tif"), read(d / "out/vsmax.tif")
        off = dist > 25.0
        vol = hfin.sum()
        spill = hfin[off].sum() / vol
        sx = (hfin * X)[off].sum() / max(hfin[off].sum(), 1e-300)
        sy = (hfin * Y)[off].sum() / max(hfin[off].sum(), 1e-300)
        cy = (hfin * Y)[~off].sum() / hfin[~off].sum()
        print(f"| {dx:g} | {(hmax > 0.1).sum() * dx * dx:.0f} | {spill:.3f} | {sx:.1f}, {sy:.1f} | {cy:.1f} | {vmax.max():.1f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
