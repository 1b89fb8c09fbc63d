#!/usr/bin/env python3
"""Talus vs AvaFrame com1DFA on the terrain cases (issue 13, part 5).

Subcommands (run with a python that has numpy and rasterio, e.g. /work/avaframe-venv/bin/python):

  prep CASE_DIR WORK_DIR [--phi-deg 25] [--rheology voellmy --voellmy-mu M --voellmy-xi X]
       [--tend-s T] [--stop-fraction F] [--density RHO]
      writes WORK_DIR/talus/<case>/{solids_vertical.tif, case.run}: the release thickness of
      release.tif (slope-normal, as AvaFrame reads it) converted to the vertical thickness Talus
      reads (h_v = h_n / cos(theta) = h_n * sqrt(1 + |grad b|^2), so both codes start with the
      same volume), and a two-phase, solids-only run-file with Coulomb bed friction (default) or
      the Voellmy law (Solid Rheology=voellmy, Voellmy Mu, Voellmy Xi; issue 19, item 4).
      --stop-fraction writes Stop At Rest Fraction (com1DFA's stopCrit, 0.01 there).

  table WORK_DIR CASE [CASE ...] [--md FILE]
      reads the AvaFrame outputs (WORK_DIR/avaframe/<case>) and the Talus outputs
      (WORK_DIR/talus/<case>/out and any out_<label> variant), computes the metrics below and
      prints a Markdown table.

Metrics (cells on the DEM grid; thicknesses compared slope-normal: Talus' vertical hsmax/hsfinal are
multiplied by cos(theta) of the DEM, AvaFrame's pft/FT are slope-normal already):
  affected area   planimetric area of cells with peak thickness > 0.1 m
  deposit area    planimetric area of cells with final thickness > 0.1 m
  peak speed      maximum of pfv (AvaFrame) / vsmax (Talus): over all cells, over the affected cells,
                  and the 99th percentile over the affected cells
  energy bound    sqrt(2 g (z_top - z_min)): frictionless free-fall speed from the release's highest
                  cell to the lowest affected cell (in comparison.json)
  travel dist.    largest horizontal distance from the release's highest cell to an affected cell
  alpha           atan((z_top - z_far) / travel distance) for that farthest affected cell
  runout          largest projection of an affected cell, measured from the release centroid, onto
                  the main flow direction: the unit vector from the release centroid to the
                  centroid of the union of all runs' affected areas (one direction per case)
  Jaccard         |A_avaframe & A_talus| / |A_avaframe | A_talus| of the affected areas, per Talus run
  along-bed speed Talus' vsmax is the horizontal speed sqrt(u^2 + v^2), com1DFA's pfv the speed along
                  the surface. Talus writes no velocity direction, so its along-bed speed
                  s |u| = sqrt(1 + (e.grad b)^2) |u| is estimated with e = the direction the front
                  moved, grad(tarrival) / |grad(tarrival)| (central differences of the arrival-time
                  map; fall line where that is undefined), given beside com1DFA's pfv (comparison.json:
                  peak_speed_bed_ms, p99_speed_bed_ms; the fall-line bound vsmax / cos(theta) as
                  peak_speed_fallline_ms)
  path runout     with --paths DIR (DIR/<case>/path_aimec.shp, AvaFrame's AIMEC path line): every
                  affected cell is projected onto the nearest point of the line; runout = the largest
                  arc length s of an affected cell minus s of the release's highest cell (path
                  oriented from its end nearer that cell); for avaHelix the straight-line runout is
                  meaningless (the path turns by about 90 deg)
"""
import argparse
import glob
import json
import math
import pathlib
import sys

import numpy as np
import rasterio

THRESH = 0.1


def read(path):
    with rasterio.open(path) as ds:
        a = ds.read(1).astype(np.float64)
        nod = ds.nodata
        prof = ds.profile
        tr = ds.transform
    if nod is not None and not (isinstance(nod, float) and math.isnan(nod)):
        a = np.where(a == nod, np.nan, a)
    return a, prof, tr


def slope_cos(dem, cell):
    """cos(theta) from centred differences (one-sided at nodata edges)."""
    z = dem.copy()
    gy, gx = np.gradient(np.where(np.isnan(z), np.nanmean(z), z), cell)
    # cells next to nodata: fall back to 0 slope contribution from the nodata side is not exact,
    # but release and flow stay well inside the valid area
    g2 = gx * gx + gy * gy
    c = 1.0 / np.sqrt(1.0 + g2)
    c[np.isnan(dem)] = np.nan
    return c


def solids_runfile(comment, dem, delta, tend_s, report_s, solids_extra="", time_extra=""):
    """A two-phase, solids-only Talus run-file: release solids_vertical.tif, bed friction delta [rad]
    (Coulomb unless solids_extra sets another Solid Rheology), K = 1, no drag, cos^4 depth pressure."""
    return f"""[Talus run file]
{comment}
[Input]
Map Directory=.
DEM={dem}
Include Initial Water=0
[Solids]
Include Initial Solids=1
Initial Solid Height=solids_vertical.tif
Initial Solid IFA={delta:.6f}
Bed Friction Equals IFA=0
Bed Friction Angle={delta:.6f}
Earth Pressure=constant
Earth Pressure Coefficient=1
Drag Law=off
{solids_extra}[Time]
End Time={tend_s / 60.0:.6f}
Timestep={report_s:g}
{time_extra}[Flow]
Slope Correction=1
Depth Pressure=cos4
[Numerics]
Precision=double
[Output]
Report Series=0
Output Directory=out
"""


def prep(args):
    case_dir = args.case_dir.resolve()
    case = case_dir.name
    out = (args.work_dir / "talus" / case).resolve()
    out.mkdir(parents=True, exist_ok=True)
    dem, prof, tr = read(case_dir / "dem.tif")
    rel, rprof, _ = read(case_dir / "release.tif")
    cell = abs(tr.a)
    cth = slope_cos(dem, cell)
    hv = np.where(rel > 0, rel / cth, 0.0)
    hv = np.nan_to_num(hv, nan=0.0)
    p = dict(rprof)
    p.update(dtype="float32", nodata=None, compress="deflate")
    with rasterio.open(out / "solids_vertical.tif", "w", **p) as ds:
        ds.write(hv.astype(np.float32), 1)
    vol_v = float(hv.sum() * cell * cell)
    phi = math.radians(args.phi_deg)
    law = "Coulomb"
    rheo = ""
    if args.rheology == "voellmy":
        law = f"Voellmy (mu = {args.voellmy_mu}, xi = {args.voellmy_xi} m/s2)"
        rheo = f"Solid Rheology=voellmy\nVoellmy Mu={args.voellmy_mu!r}\nVoellmy Xi={args.voellmy_xi!r}\n"
    if args.density is not None:
        rheo += f"Initial Solid Density={args.density!r}\n"
    stop = f"Stop At Rest Fraction={args.stop_fraction!r}\n" if args.stop_fraction else ""
    run = solids_runfile(f"""# {case}: {law} comparison with AvaFrame com1DFA (tools/peers/terrain_compare.py prep).
# Release = {case_dir}/release.tif (slope-normal, 1 m) converted to vertical thickness.
# Vertical release volume sum(h_v dx dy) = {vol_v:.1f} m3.""", f"{case_dir}/dem.tif", phi, args.tend_s, 10, rheo, stop)
    (out / "case.run").write_text(run)
    print(json.dumps({"case": case, "run": str(out / "case.run"), "release_volume_vertical_m3": vol_v,
                      "release_cells": int((rel > 0).sum())}))


def front_stretch(dem, tarr, cell):
    """s = sqrt(1 + (e.grad b)^2) with e the direction of grad(tarrival) (the front's direction of
    travel); the fall-line value sqrt(1 + |grad b|^2) where the arrival-time gradient is undefined."""
    z = np.where(np.isnan(dem), np.nanmean(dem), dem)
    by, bx = np.gradient(z, cell)
    ty, tx = np.gradient(tarr, cell)  # NaN next to cells never reached
    n = np.hypot(tx, ty)
    ok = np.isfinite(n) & (n > 0)
    w = np.where(ok, (tx * bx + ty * by) / np.where(ok, n, 1.0), np.hypot(bx, by))
    return np.sqrt(1.0 + w * w)


def path_coords(path_shp, x, y):
    """Arc length s of the nearest point of the polyline in path_shp for each (x, y)."""
    import shapefile
    pts = np.asarray(shapefile.Reader(str(path_shp)).shapes()[0].points, dtype=np.float64)
    best_d = np.full(x.shape, np.inf)
    best_s = np.zeros(x.shape)
    s0 = 0.0
    for (ax, ay), (bx, by) in zip(pts[:-1], pts[1:]):
        vx, vy = bx - ax, by - ay
        L = math.hypot(vx, vy)
        if L == 0:
            continue
        t = np.clip(((x - ax) * vx + (y - ay) * vy) / (L * L), 0.0, 1.0)
        d = np.hypot(x - ax - t * vx, y - ay - t * vy)
        better = d < best_d
        best_d = np.where(better, d, best_d)
        best_s = np.where(better, s0 + t * L, best_s)
        s0 += L
    return best_s, best_d, s0


def metrics(peak, final, speed, dem, rel, cell, tr, direction=None, spath=None, speed_bed=None):
    nr, nc = dem.shape
    rows, cols = np.mgrid[0:nr, 0:nc]
    x = tr.c + (cols + 0.5) * tr.a
    y = tr.f + (rows + 0.5) * tr.e
    aff = np.nan_to_num(peak, nan=0.0) > THRESH
    dep = np.nan_to_num(final, nan=0.0) > THRESH
    relm = rel > 0
    zr = np.where(relm, dem, -np.inf)
    itop = np.unravel_index(np.argmax(zr), zr.shape)
    xt, yt, zt = x[itop], y[itop], dem[itop]
    d = np.hypot(x - xt, y - yt)
    dm = np.where(aff, d, -1)
    ifar = np.unravel_index(np.argmax(dm), dm.shape)
    res = {
        "affected_m2": float(aff.sum() * cell * cell),
        "deposit_m2": float(dep.sum() * cell * cell),
        "peak_thickness_m": float(np.nanmax(peak)),
        "peak_speed_ms": float(np.nanmax(speed)),
        "peak_speed_aff_ms": float(np.nanmax(np.where(aff, speed, np.nan))),
        "p99_speed_aff_ms": float(np.nanpercentile(speed[aff], 99)),
        "energy_bound_ms": float(math.sqrt(2 * 9.81 * (zt - np.nanmin(np.where(aff, dem, np.nan))))),
        "travel_m": float(dm[ifar]),
        "alpha_deg": float(math.degrees(math.atan2(zt - dem[ifar], dm[ifar]))) if dm[ifar] > 0 else float("nan"),
        "z_far": float(dem[ifar]),
    }
    if speed_bed is not None:
        res["peak_speed_bed_ms"] = float(np.nanmax(np.where(aff, speed_bed, np.nan)))
        res["p99_speed_bed_ms"] = float(np.nanpercentile(speed_bed[aff], 99))
        ib = np.unravel_index(np.nanargmax(np.where(aff, speed_bed, np.nan)), aff.shape)
        res["peak_speed_bed_at"] = {"row": int(ib[0]), "col": int(ib[1]), "z": float(dem[ib])}
    if spath is not None:
        s_path, s_len = spath
        s_top = s_path[itop]
        if s_top > s_len / 2:  # orient the path from the end nearer the release top
            s_path, s_top = s_len - s_path, s_len - s_top
        res["path_runout_m"] = float(np.where(aff, s_path, -np.inf).max() - s_top)
    xc, yc = x[relm].mean(), y[relm].mean()
    if direction is not None:
        proj = (x - xc) * direction[0] + (y - yc) * direction[1]
        res["runout_m"] = float(np.where(aff, proj, -np.inf).max())
    return res, aff, (x, y, xc, yc)


def first(pattern):
    g = sorted(glob.glob(pattern))
    if not g:
        raise FileNotFoundError(pattern)
    return g[0]


def on_grid(a, shape):
    """AvaFrame runs on the DEM grid here (meshCellSize = DEM cell size); if it remeshed anyway,
    map its lower-left-anchored grid onto the DEM grid by index (see the case PROVENANCE.md)."""
    if a.shape == shape:
        return a
    out = np.full(shape, np.nan)
    r = min(a.shape[0], shape[0])
    c = min(a.shape[1], shape[1])
    out[shape[0] - r:, :c] = a[a.shape[0] - r:, :c]
    return out


def table(args):
    work = args.work_dir.resolve()
    lines = []
    hdr = ("| case | code | sim. time [s] | wall [s] | peak thickness [m] | peak speed [m/s]: all / affected cells / p99 affected | affected area > 0.1 m [m2] "
           "| deposit area > 0.1 m [m2] | runout along flow dir. [m] | travel dist. from release top [m] | alpha [deg] |")
    lines.append(hdr)
    lines.append("|" + "---|" * 11)
    jac = []
    bed = []
    raw = {}
    for case in args.cases:
        cdir = pathlib.Path(args.data) / case
        dem, _, tr = read(cdir / "dem.tif")
        rel, _, _ = read(cdir / "release.tif")
        cell = abs(tr.a)
        cth = slope_cos(dem, cell)
        runs = {}
        # AvaFrame
        adir = work / "avaframe" / case
        if (adir / "run_info.json").exists():
            pk = adir / "Outputs" / "com1DFA" / "peakFiles"
            info = json.loads((adir / "run_info.json").read_text())
            pft = on_grid(read(first(str(pk / "*_pft.tif")))[0], dem.shape)
            pfv = on_grid(read(first(str(pk / "*_pfv.tif")))[0], dem.shape)
            ft = on_grid(read(first(str(pk / "*_FT.tif")))[0], dem.shape)
            ts = sorted(glob.glob(str(pk / "timeSteps" / "*_FT_t*.tif")))
            tfin = float(ts[-1].rsplit("_t", 1)[1][:-4]) if ts else float("nan")
            runs["AvaFrame com1DFA"] = (pft, ft, pfv, tfin, info["wall_s"], pfv, pfv)
        # Talus: out (defaults) and out_<label> (variants of terrain_avaframe.sh's TALUS_SET)
        for tdir in sorted((work / "talus" / case).glob("out*")):
            if not (tdir / "summary.json").exists():
                continue
            s = json.loads((tdir / "summary.json").read_text())
            hs = read(tdir / "hsmax.tif")[0] * cth
            hf = read(tdir / "hsfinal.tif")[0] * cth
            vs = read(tdir / "vsmax.tif")[0]
            tsim = s.get("simulated_s", s.get("simulated_seconds", s.get("end_time_s", float("nan"))))
            wall = s.get("wall_s", s.get("wall_time_s", float("nan")))
            label = tdir.name[4:]
            runs["Talus" + (" " + label if label else "") + " (" + str(s.get("status", "?")) + ")"] = (
                hs, hf, vs, tsim, wall, vs * front_stretch(dem, read(tdir / "tarrival.tif")[0], cell)
                if (tdir / "tarrival.tif").exists() else vs / cth, vs / cth)
        # common direction: release centroid -> centroid of the union of all runs' affected areas
        masks = {k: np.nan_to_num(v[0], nan=0.0) > THRESH for k, v in runs.items()}
        if not masks:
            continue
        union = np.logical_or.reduce(list(masks.values()))
        _, _, (x, y, xc, yc) = metrics(*next(iter(runs.values()))[:3], dem, rel, cell, tr)
        dx, dy = x[union].mean() - xc, y[union].mean() - yc
        n = math.hypot(dx, dy)
        direction = (dx / n, dy / n)
        raw[case] = {"direction": direction}
        spath = None
        if args.paths and (pathlib.Path(args.paths) / case / "path_aimec.shp").exists():
            sp, _, slen = path_coords(pathlib.Path(args.paths) / case / "path_aimec.shp", x, y)
            spath = (sp, slen)
        for name, (pk_, fin, spd, tsim, wall, spd_bed, spd_fall) in runs.items():
            m, aff, _ = metrics(pk_, fin, spd, dem, rel, cell, tr, direction, spath, spd_bed)
            m["peak_speed_fallline_ms"] = float(np.nanmax(np.where(aff, spd_fall, np.nan)))
            m.update(sim_time_s=tsim, wall_s=wall)
            raw[case][name] = m
            lines.append(f"| {case} | {name} | {tsim:.1f} | {wall:.1f} | {m['peak_thickness_m']:.2f} | "
                         f"{m['peak_speed_ms']:.1f} / {m['peak_speed_aff_ms']:.1f} / {m['p99_speed_aff_ms']:.1f} | {m['affected_m2']:.0f} | {m['deposit_m2']:.0f} | "
                         f"{m['runout_m']:.0f} | {m['travel_m']:.0f} | {m['alpha_deg']:.1f} |")
            bed.append(f"| {case} | {name} | {m['peak_speed_bed_ms']:.1f} / {m['p99_speed_bed_ms']:.1f} | "
                       + (f"{m['path_runout_m']:.0f} |" if "path_runout_m" in m else "- |"))
        a = masks.get("AvaFrame com1DFA")
        for name, b in masks.items():
            if a is None or b is a:
                continue
            j = (a & b).sum() / max(1, (a | b).sum())
            jac.append(f"| {case} | {name} | {j:.3f} | {(a & b).sum() * cell * cell:.0f} | {(a | b).sum() * cell * cell:.0f} |")
            raw[case][name]["jaccard"] = float(j)
    lines.append("")
    if jac:
        lines.append("| case | Talus run | Jaccard of affected areas vs com1DFA | intersection [m2] | union [m2] |")
        lines.append("|---|---|---|---|---|")
        lines.extend(jac)
    if bed:
        lines.append("")
        lines.append("| case | code | peak / p99 along-bed speed, affected cells [m/s] (com1DFA: pfv; Talus: vsmax * s in the front's direction) | runout along the AIMEC path from the release top [m] |")
        lines.append("|---|---|---|---|")
        lines.extend(bed)
    txt = "\n".join(lines) + "\n"
    print(txt)
    (work / "comparison.json").write_text(json.dumps(raw, indent=2, default=float))
    if args.md:
        pathlib.Path(args.md).write_text(txt)


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("prep")
    p.add_argument("case_dir", type=pathlib.Path)
    p.add_argument("work_dir", type=pathlib.Path)
    p.add_argument("--phi-deg", type=float, default=25.0)
    p.add_argument("--tend-s", type=float, default=150.0)
    p.add_argument("--rheology", choices=["coulomb", "voellmy"], default="coulomb")
    p.add_argument("--voellmy-mu", type=float, default=0.155)
    p.add_argument("--voellmy-xi", type=float, default=4000.0)
    p.add_argument("--stop-fraction", type=float, default=0.0)
    p.add_argument("--density", type=float, help="Initial Solid Density [kg/m3] (default: Talus' own)")
    t = sub.add_parser("table")
    t.add_argument("work_dir", type=pathlib.Path)
    t.add_argument("cases", nargs="+")
    t.add_argument("--data", default="/work/shared/data/terrain")
    t.add_argument("--md")
    t.add_argument("--paths", help="folder with <case>/path_aimec.shp (AvaFrame's AIMEC path lines)")
    a = ap.parse_args()
    prep(a) if a.cmd == "prep" else table(a)


if __name__ == "__main__":
    sys.exit(main())
