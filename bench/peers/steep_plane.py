#!/usr/bin/env python3
"""Diagnostic: a thin sheet on a steep plane with Manning friction (not part of the timed study).

  steep_plane.py WORK [--angle 35] [--h0 0.2] [--dx 5,2.5,1]

A uniform sheet h0 on the plane z = 1000 - tan(angle) x (flow along x, 4 cells wide, walls on the
sides, open / extrapolation ends) accelerates to the normal flow of the classical equations,
u_n = sqrt(S) h^(2/3) / n with S = tan(angle) (Talus with Slope Correction=0, GeoClaw). The
upstream end thins and the downstream end drains; the middle stays uniform. After t = 20 s the
script compares the mean depth and speed of cells in x in [0.55 L, 0.75 L] (L = 600 m; the upstream
disturbance travels about 5/3 u_n t) with u_n at that depth, for both codes at each dx.
This is the regime of kot_dambreak's thin tail on 30-45 degree slopes with 5 m cells: the bed
falls tan(angle) dx (3.5 m at 35 degrees) per cell, far more than the depth.
"""
import argparse
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import geoclaw_cases as gc  # noqa: E402
import peers_io  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("--angle", type=float, default=35.0)
    ap.add_argument("--h0", type=float, default=0.2)
    ap.add_argument("--n", type=float, default=0.05)
    ap.add_argument("--dx", default="5,2.5,1")
    ap.add_argument("--t", type=float, default=20.0)
    a = ap.parse_args()
    work = os.path.join(os.path.abspath(a.work), "steep_plane")
    S = math.tan(math.radians(a.angle))
    L, ny = 600.0, 4
    lines = []

    def emit(text):
        print(text, flush=True)
        lines.append(text)

    emit(f"Steep plane (`steep_plane.py`): a {a.h0} m sheet on a {a.angle:g} degree plane (S = {S:.4f}), "
        f"Manning {a.n}, t = {a.t} s, 1 thread; speed in the middle of the plane against the normal-flow "
        f"speed u_n = sqrt(S) h^(2/3) / n of the classical equations (u_n(h0) = "
        f"{math.sqrt(S) * a.h0 ** (2 / 3) / a.n:.3f} m/s).")
    emit("")
    emit("| code | dx m | mean h m | mean u m/s | u_n(h) m/s | u / u_n |")
    emit("|---|---|---|---|---|---|")
    for dx in [float(v) for v in a.dx.split(",")]:
        nx = int(round(L / dx))
        d = os.path.join(work, "dx" + gc.res_name(dx))
        os.makedirs(d, exist_ok=True)
        xc = (np.arange(nx) + 0.5) * dx
        z = np.tile(1000.0 - S * xc, (ny, 1))
        h = np.full((ny, nx), a.h0)
        gc.write_raster(os.path.join(d, "dem.tif"), gc.Raster(z, 0.0, ny * dx, dx))
        gc.write_raster(os.path.join(d, "water.tif"), gc.Raster(h, 0.0, ny * dx, dx))
        with open(os.path.join(d, "talus.run"), "w") as f:
            f.write(gc.talus_run_text(a.n, a.t, "double", "open"))
        # Talus: walls on the sides are not separately selectable from the open ends, so the
        # 4-cell strip has open sides too; the flow is along x, so nothing leaves sideways.
        out = os.path.join(d, "talus_out")
        peers_io.run_talus(os.path.join(d, "talus.run"), out)
        ht = gc.read_raster(os.path.join(out, "hffinal.tif")).values
        ut = gc.read_raster(os.path.join(out, "vffinal.tif")).values
        # GeoClaw
        cdir = os.path.join(d, "geoclaw_case")
        gc.geoclaw_case_quiet(cdir, z, h, dx, tfinal=a.t, nout=1, bc="extrap", manning=a.n, wall_height=0.0,
                              out_format="ascii", fgmax=False)
        q, t = peers_io.run_geoclaw_case(cdir, os.path.join(d, "geoclaw_out"), nx, ny, dx)
        hg = q[0]
        ug = np.hypot(q[1], q[2]) / np.maximum(q[0], 1e-12)
        sel = slice(int(0.55 * nx), int(0.75 * nx))
        for code, hh, uu in (("Talus (double, slope corr. off)", ht, ut), ("GeoClaw", hg, ug)):
            hm = float(np.mean(hh[:, sel]))
            um = float(np.mean(uu[:, sel]))
            un = math.sqrt(S) * hm ** (2 / 3) / a.n
            emit(f"| {code} | {dx:g} | {hm:.4f} | {um:.3f} | {un:.3f} | {um / un:.3f} |")
    with open(os.path.join(os.path.dirname(work), "steep_plane.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
