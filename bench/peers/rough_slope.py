#!/usr/bin/env python3
"""Diagnostic: a water sheet on a steep slope whose DEM is rough at the scale of its cells.

  rough_slope.py WORK [--amp 0.5] [--t 30] [--limiters mc,vanleer,minmod]

The regime of kot_dambreak's sheets on 30-45 degree slopes with 5 m cells, with a known answer
(the same scene on finer cells): a plane z = 0.7 (400 - y) (35 degrees) plus noise given on a 5 m
lattice (normal, standard deviation `amp`, seed 7) and refined bilinearly (geoclaw_cases.refine_bilinear)
to 2.5 m and 1.25 m, so every grid samples the same continuous bed. 2 m of water over 40 m x 40 m near
the top at rest, Manning 0.05, open edges, t = 30 s. Talus (double, slope correction off: the
classical equations) with each limiter and GeoClaw (one level, its defaults) run on the three grids;
the table gives the volume left, the area deeper than 1 cm, the sheet's centre of mass along the
slope, and the distance sum|h - H| / sum H of each map from the same code's 1.25 m map (block means).
Writes WORK/rough_slope.md.
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import geoclaw_cases as gc  # noqa: E402
import peers_io  # noqa: E402

LEVELS = ((1, "5"), (2, "2.5"), (4, "1.25"))
NX5, NY5, DX5 = 40, 80, 5.0


def block_mean(a, f):
    ny, nx = a.shape
    return a.reshape(ny // f, f, nx // f, f).mean(axis=(1, 3))


def build(work, amp, t_end):
    rng = np.random.default_rng(7)
    yc = (np.arange(NY5) + 0.5) * DX5
    dem5 = gc.Raster(0.7 * (NY5 * DX5 - yc)[:, None] + amp * rng.standard_normal((NY5, NX5)), 0.0, NY5 * DX5, DX5)
    dirs = {}
    for f, name in LEVELS:
        d = os.path.join(work, "r" + gc.res_name(DX5 / f))
        os.makedirs(d, exist_ok=True)
        dem = dem5 if f == 1 else gc.refine_bilinear(dem5, f)
        ny, nx = dem.values.shape
        xx = (np.arange(nx) + 0.5) * dem.dx
        yy = (np.arange(ny) + 0.5) * dem.dx
        h = np.where(((xx > 80) & (xx < 120))[None, :] & ((yy > 20) & (yy < 60))[:, None], 2.0, 0.0)
        gc.write_raster(os.path.join(d, "dem.tif"), gc.Raster(dem.values, 0.0, NY5 * DX5, dem.dx))
        gc.write_raster(os.path.join(d, "water.tif"), gc.Raster(h, 0.0, NY5 * DX5, dem.dx))
        with open(os.path.join(d, "talus.run"), "w") as fo:
            fo.write(gc.talus_run_text(0.05, t_end, "double", "open"))
        z = gc.read_raster(os.path.join(d, "dem.tif")).values
        gc.geoclaw_case_quiet(os.path.join(d, "geoclaw_case"), z, h, dem.dx, tfinal=t_end, nout=1, bc="extrap",
                              manning=0.05, wall_height=0.0, out_format="binary64", fgmax=False)
        dirs[name] = (d, f, nx, ny, dem.dx)
    return dirs


def run_talus(d, limiter):
    out = os.path.join(d, "talus_" + limiter.replace("@", "_"))
    peers_io.run_talus(os.path.join(d, "talus.run"), out, peers_io.talus_variant(limiter))
    return np.nan_to_num(gc.read_raster(os.path.join(out, "hffinal.tif")).values)


def run_geoclaw(d, nx, ny, dx):
    q, _ = peers_io.run_geoclaw_case(os.path.join(d, "geoclaw_case"), os.path.join(d, "geoclaw_out"), nx, ny, dx)
    return np.nan_to_num(q[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("--amp", type=float, default=0.5)
    ap.add_argument("--t", type=float, default=30.0)
    ap.add_argument("--limiters", default="mc,vanleer,minmod,mc@hancock,minmod@hancock")
    ap.add_argument("--no-geoclaw", action="store_true", help="Talus only (a variant's kernels, TALUS_KERNEL_DIR)")
    a = ap.parse_args()
    work = os.path.join(os.path.abspath(a.work), "rough_slope")
    dirs = build(work, a.amp, a.t)
    emit = peers_io.MarkdownLog()
    emit(f"Rough slope (`rough_slope.py`): 35 degree plane plus 5 m noise of standard deviation {a.amp} m "
         f"(bilinear below 5 m), 2 m x 40 m x 40 m of water, Manning 0.05, t = {a.t} s, one thread each. "
         "Distance: sum|h - H| / sum H from the same code's 1.25 m map (block means).")
    emit("")
    emit("| code | cells m | volume left m3 | area > 1 cm m2 | centre of mass along the slope m | distance to own 1.25 m |")
    emit("|---|---|---|---|---|---|")
    codes = [("Talus " + lim, lambda d, nx, ny, dx, lim=lim: run_talus(d, lim)) for lim in a.limiters.split(",")]
    if not a.no_geoclaw:
        codes.append(("GeoClaw", lambda d, nx, ny, dx: run_geoclaw(d, nx, ny, dx)))
    for code, runner in codes:
        maps = {name: runner(d, nx, ny, dx) for name, (d, f, nx, ny, dx) in dirs.items()}
        ref = maps["1.25"]
        for name, (d, f, nx, ny, dx) in dirs.items():
            h = maps[name]
            y = (np.arange(h.shape[0]) + 0.5) * dx
            centre = float((h * y[:, None]).sum() / h.sum())
            dist = "–"
            if name != "1.25":
                r = block_mean(ref, 4 // f)
                dist = f"{np.abs(h - r).sum() / r.sum():.3f}"
            emit(f"| {code} | {name} | {h.sum() * dx * dx:.0f} | {np.sum(h > 0.01) * dx * dx:.0f} | {centre:.1f} | {dist} |")
    emit.save(os.path.join(os.path.dirname(work), "rough_slope.md"))


if __name__ == "__main__":
    main()
