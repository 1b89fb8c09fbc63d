#!/usr/bin/env python3
"""Roll waves on a steep plane, Talus and GeoClaw side by side: how sharply each code resolves the
bores that set a steep flood path's peak depths.

A plane of slope S = 0.25 (14 degrees), 1600 m long and eight cells wide (GeoClaw needs more than four), carries h = 1 m of water at
rest with a small wave, h = 1 + 0.05 cos(2 pi x / 100 m), Manning n = 0.05, open edges. The water
accelerates towards Manning's uniform flow (u0 = 10 m/s, Froude 3.2), which is unstable above Froude
3/2, and the wave grows into a train of roll waves (bores) that saturate within about 30 s
(tests/verification/test_roll_waves.cpp checks the linear growth against the dispersion relation).
At t = 40 s the window x >= 700 m (beyond the reach of the upper edge's disturbance, u0 + c = 13 m/s)
holds seven wavelengths. Printed per code and cell size: the largest depth in the window, the mean of
the seven crest depths, and the distance sum|h - H| / sum|H - 1| of the depth profile from the same
code's finest profile (block means).

  roll_waves.py WORK [--cells 5,2.5,1.25,0.625] [--talus-limiters mc,vanleer]    (about 2 minutes)

The table also goes to WORK/roll_waves.md (geoclaw_compare.sh step `roll` adds it to the report).

Environment: TALUS_BIN, GEOCLAW_EXE (as geoclaw_compare.sh sets them).
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import geoclaw_cases as gc  # noqa: E402
import peers_io  # noqa: E402

SLOPE, H0, EPS, WAVE, LENGTH, ROWS, MANNING = 0.25, 1.0, 0.05, 100.0, 1600.0, 8, 0.05
WINDOW0 = 700.0


def build(work, dx, t_end):
    d = os.path.join(work, "r" + gc.res_name(dx))
    os.makedirs(d, exist_ok=True)
    nx = int(round(LENGTH / dx))
    x = (np.arange(nx) + 0.5) * dx
    k = 2 * np.pi / WAVE
    avg = np.sin(k * dx / 2) / (k * dx / 2)  # cell averages of the cosine
    z = np.repeat((SLOPE * (LENGTH - x))[None, :], ROWS, axis=0)
    h = np.repeat((H0 + EPS * avg * np.cos(k * x))[None, :], ROWS, axis=0)
    gc.write_raster(os.path.join(d, "dem.tif"), gc.Raster(z, 0.0, ROWS * dx, dx))
    gc.write_raster(os.path.join(d, "water.tif"), gc.Raster(h, 0.0, ROWS * dx, dx))
    with open(os.path.join(d, "talus.run"), "w") as fo:
        fo.write(gc.talus_run_text(MANNING, t_end, "double", "open"))
    z = gc.read_raster(os.path.join(d, "dem.tif")).values
    gc.geoclaw_case_quiet(os.path.join(d, "geoclaw_case"), z, h, dx, tfinal=t_end, nout=1, bc="extrap",
                          manning=MANNING, wall_height=0.0, out_format="binary64", fgmax=False)
    return d, nx


def run_talus(d, limiter):
    out = os.path.join(d, "talus_" + limiter.replace("@", "_"))
    peers_io.run_talus(os.path.join(d, "talus.run"), out, peers_io.talus_variant(limiter))
    return np.nan_to_num(gc.read_raster(os.path.join(out, "hffinal.tif")).values)[ROWS // 2]


def run_geoclaw(d, nx, dx):
    q, _ = peers_io.run_geoclaw_case(os.path.join(d, "geoclaw_case"), os.path.join(d, "geoclaw_out"), nx, ROWS, dx)
    return np.nan_to_num(q[0])[ROWS // 2]


def crests(profile, dx):
    """Depth of each wave's crest: the maximum of each wavelength-long segment of the window."""
    i0 = int(round(WINDOW0 / dx))
    n = int(round(WAVE / dx))
    w = profile[i0:]
    return np.array([w[j:j + n].max() for j in range(0, len(w) - n + 1, n)])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("--cells", default="5,2.5,1.25,0.625")
    ap.add_argument("--talus-limiters", default="mc,vanleer,mc@hancock")
    ap.add_argument("--t", type=float, default=40.0)
    a = ap.parse_args()
    work = os.path.join(os.path.abspath(a.work), "roll_waves")
    cells = [float(c) for c in a.cells.split(",")]
    cases = {dx: build(work, dx, a.t) for dx in cells}
    emit = peers_io.MarkdownLog()
    emit(f"Roll waves (`roll_waves.py`): plane of slope {SLOPE}, h = {H0} m + {EPS} m cos(2 pi x / {WAVE:.0f} m) "
         f"at rest, Manning {MANNING}, t = {a.t:.0f} s, window x >= {WINDOW0:.0f} m; one thread each. Distance: "
         "sum|h - H| / sum|H - 1 m| from the same code's finest profile (block means).")
    emit("")
    emit("| code | cell m | max depth m | mean crest depth m | distance to own finest |")
    emit("|---|---|---|---|---|")
    codes = [("Talus " + lim, lambda d, nx, dx, lim=lim: run_talus(d, lim)) for lim in a.talus_limiters.split(",")]
    codes.append(("GeoClaw", lambda d, nx, dx: run_geoclaw(d, nx, dx)))
    finest = min(cells)
    for code, runner in codes:
        prof = {dx: runner(d, nx, dx) for dx, (d, nx) in cases.items()}
        ref = prof[finest]
        for dx in cells:
            p = prof[dx]
            f = int(round(dx / finest))
            rb = ref.reshape(-1, f).mean(axis=1)
            i0 = int(round(WINDOW0 / dx))
            dist = np.abs(p[i0:] - rb[i0:]).sum() / np.abs(rb[i0:] - H0).sum()
            emit(f"| {code} | {dx:g} | {p[i0:].max():.3f} | {crests(p, dx).mean():.3f} | "
                 f"{'–' if dx == finest else f'{dist:.3f}'} |")
    emit.save(os.path.join(os.path.dirname(work), "roll_waves.md"))


if __name__ == "__main__":
    main()
