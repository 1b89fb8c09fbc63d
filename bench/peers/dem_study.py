#!/usr/bin/env python3
"""Grid study of a water release on any real-terrain scene, Talus beside GeoClaw (issue 21, item 1:
"at 5 m on kot_dambreak and on one more real DEM"). kot_dambreak has its own, timed study
(geoclaw_compare.sh steps kot and grid); this one measures accuracy only, one run per code and grid.

  dem_study.py CASE_DIR WORK [--talus-levels 5,2.5,1.25] [--geoclaw-levels 5,2.5] [--radius 40]

CASE_DIR is a scene made by tools/make_example_scene.py (dem.tif, water.tif and one run-file; e.g.
data/alr_dambreak): a flat-topped water column in a disc of `--radius` m. The column is rebuilt on
each grid as that script builds it (the same centre, radius and surface level, read back from
water.tif), the DEM is refined bilinearly (or coarsened by block means), and both codes get the
very same cells (GeoClaw's topography and initial water through geoclaw_cases.geoclaw_case, whose
cell averages equal the DEM). Talus runs with the slope correction off (the equations GeoClaw
solves) in float (PEERS_GRID_TALUS_CONFIG of peers_run.py); GeoClaw with its defaults on one
thread and dry tolerance 1e-6 m. End time and Manning's n come from the scene's run-file.

Writes WORK/results.md: per run the inundated area (> 1 cm), the median peak depth, and the map
distance sum|a - B| / sum|B| of its max-depth map against the finest Talus and the finest GeoClaw
map, both block-averaged to the coarser grid (compare_maps.distance). Environment as peers_run.py
(TALUS_BIN, GEOCLAW_EXE; geoclaw_compare.sh --only setup,dem sets them).
"""
import argparse
import glob
import json
import math
import os
import sys

import numpy as np

import compare_maps
import geoclaw_cases as gc
import peers_io
import peers_run

WET = compare_maps.WET


def read_runfile(path):
    keys = {}
    for line in open(path).read().splitlines():
        if "=" in line and not line.startswith("["):
            k, v = line.split("=", 1)
            keys[k.strip()] = v.strip()
    return keys


def column_of(dem, water):
    """Centre (x, y) and surface level of the scene's water column, read back from its cells."""
    x, y = dem.centres()
    h = np.nan_to_num(water.values)
    wet = h > 0
    if not wet.any():
        sys.exit("dem_study: water.tif holds no water")
    X, Y = np.meshgrid(x, y)
    eta = float(np.max((np.nan_to_num(dem.values) + h)[wet]))
    # the disc is centred on a cell centre: snap the mean of the wet centres to it
    col = int(round((X[wet].mean() - x[0]) / dem.dx))
    row = int(round((y[0] - Y[wet].mean()) / dem.dx))
    return float(x[col]), float(y[row]), eta


def column_on(dem, cx, cy, radius, eta):
    """The scene's column on `dem` (geoclaw_cases.water_column); a relative 1e-9 on the radius keeps
    cells whose centre lies exactly on the circle inside, as tools/make_example_scene.py does."""
    return gc.water_column(dem, cx, cy, radius * (1 + 1e-9), eta)


def prepare(case_dir, work, case, levels, gc_levels, radius):
    runfiles = glob.glob(os.path.join(case_dir, "*.run"))
    if len(runfiles) != 1:
        sys.exit(f"dem_study: expected one run-file in {case_dir}, found {len(runfiles)}")
    keys = read_runfile(runfiles[0])
    tfinal = float(keys.get("End Time", "1.5")) * 60.0  # run-file times are in minutes
    manning = float(keys.get("Manning", "0.05"))
    dem0 = gc.read_raster(os.path.join(case_dir, "dem.tif"))
    water0 = gc.read_raster(os.path.join(case_dir, "water.tif"))
    cx, cy, eta = column_of(dem0, water0)
    rebuilt = gc.f32(column_on(dem0, cx, cy, radius, eta)).values
    diff = float(np.nanmax(np.abs(rebuilt - np.nan_to_num(water0.values))))
    print(f"{case}: column at ({cx:.3f}, {cy:.3f}), level {eta:.2f} m, radius {radius} m; rebuilt on the "
          f"scene's grid: max |diff| {diff:.3g} m")
    if diff > 1e-3:
        sys.exit("dem_study: the water column of the scene is not a flat-topped disc of that radius")
    wall = float(math.ceil((np.nanmax(dem0.values) + 500.0) / 100.0) * 100.0)
    info = dict(tfinal=tfinal, manning=manning, column=[cx, cy, eta, radius], grids={})
    for res in sorted(set(levels) | set(gc_levels), reverse=True):
        name = case + "_r" + gc.res_name(res)
        gdir = os.path.join(work, "grids", name)
        os.makedirs(gdir, exist_ok=True)
        ratio = res / dem0.dx
        if abs(ratio - 1.0) < 1e-6:
            dem, water = dem0, water0
        elif ratio > 1:
            dem = gc.f32(gc.coarsen_mean(dem0, int(round(ratio))))
            water = gc.f32(column_on(dem, cx, cy, radius, eta))
        else:
            dem = gc.f32(gc.refine_bilinear(dem0, int(round(1.0 / ratio))))
            water = gc.f32(column_on(dem, cx, cy, radius, eta))
        gc.write_raster(os.path.join(gdir, "dem.tif"), dem)
        gc.write_raster(os.path.join(gdir, "water.tif"),
                        gc.Raster(np.nan_to_num(water.values), water.ulx, water.uly, water.dx, water.wkt),
                        nodata=-9999.0)
        with open(os.path.join(gdir, "talus.run"), "w") as fo:
            fo.write(gc.talus_runfile(runfiles[0], "dem.tif", "water.tif"))
        dem_r = gc.read_raster(os.path.join(gdir, "dem.tif"))
        h_r = np.nan_to_num(gc.read_raster(os.path.join(gdir, "water.tif")).values)
        h_r[np.isnan(dem_r.values)] = 0.0
        if res in gc_levels:
            gc.geoclaw_case_quiet(os.path.join(work, "geoclaw", name), dem_r.values, h_r, dem_r.dx,
                                  tfinal=tfinal, nout=6, bc="extrap", manning=manning, wall_height=wall,
                                  out_format="binary64", fgmax=True)
        info["grids"][name] = dict(res=res, dx=dem_r.dx, nx=dem_r.nx, ny=dem_r.ny,
                                   volume_m3=float(h_r.sum() * dem_r.dx ** 2))
        print(f"  {name}: {dem_r.nx} x {dem_r.ny} cells of {dem_r.dx:.4f} m, water "
              f"{info['grids'][name]['volume_m3']:.1f} m3")
    json.dump(info, open(os.path.join(work, "grids", case + ".json"), "w"), indent=1)
    return info


def distance(a, dxa, b, dxb):
    """compare_maps.distance on the coarser of the two grids (a finer map is block-averaged first)."""
    if dxa < dxb * (1 - 1e-9):
        a, dxa = compare_maps.aggregate(a, int(round(dxb / dxa))), dxb
    return compare_maps.distance(a, dxa, b, dxb)[0]


def report(work, case, levels, gc_levels):
    recs = {}
    for r in peers_run.load_records(work):
        if r.get("rc") == 0 and r["case"].startswith(case + "_r"):
            recs[(r["code"], r["case"])] = r  # the last successful run of each
    rows = [("talus", case + "_r" + gc.res_name(v), v) for v in sorted(levels, reverse=True)]
    rows += [("geoclaw", case + "_r" + gc.res_name(v), v) for v in sorted(gc_levels, reverse=True)]
    maps = {k: compare_maps.hmax_map(work, recs[k]["key"], {"out": recs[k]["out_dir"]}) for k in [(c, n) for c, n, _ in rows] if k in recs}
    ref_t = ("talus", case + "_r" + gc.res_name(min(levels)))
    ref_g = ("geoclaw", case + "_r" + gc.res_name(min(gc_levels)))
    out = peers_io.MarkdownLog()
    out(f"# Water release on {case}: grid study, Talus and GeoClaw (bench/peers/dem_study.py)")
    out("")
    out(f"Talus: {peers_run.GRID_TALUS_CONFIG} (slope correction off), one run per grid; GeoClaw 5.14 "
        f"defaults, dry tolerance 1e-6 m; both on two threads. Distances: sum|a - B| / sum|B| of max-depth maps "
        f"on the coarser grid of the two (the finer map block-averaged).")
    out("")
    out(f"| code | grid [m] | steps | wall [s] | inundated area > 1 cm [m²] | median peak depth [m] | "
        f"to Talus {min(levels):g} m | to GeoClaw {min(gc_levels):g} m |")
    out("|---|---|---|---|---|---|---|---|")
    table = {}
    for code, name, res in rows:
        if (code, name) not in maps:
            out(f"| {code} | {res:g} | (no run) | | | | | |")
            continue
        a, dxa = maps[(code, name)]
        st = compare_maps.map_stats(a, dxa)
        d_t = distance(a, dxa, *maps[ref_t]) if ref_t in maps and ref_t != (code, name) else None
        d_g = distance(a, dxa, *maps[ref_g]) if ref_g in maps and ref_g != (code, name) else None
        r = recs[(code, name)]
        table[f"{code}/{name}"] = dict(st, to_talus_ref=d_t, to_geoclaw_ref=d_g, steps=r.get("steps"),
                                       wall_s=r["wall_s"])
        f3 = lambda v: "–" if v is None else f"{v:.3f}"
        out(f"| {code} | {res:g} | {r.get('steps', '')} | {r['wall_s']:.1f} | {st['area_m2']:.0f} | "
            f"{st['median_hmax']:.2f} | {f3(d_t)} | {f3(d_g)} |")
    out.save(os.path.join(work, f"results_{case}.md"))
    json.dump(table, open(os.path.join(work, f"results_{case}.json"), "w"), indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case_dir")
    ap.add_argument("work")
    ap.add_argument("--talus-levels", default="5,2.5,1.25")
    ap.add_argument("--geoclaw-levels", default="5,2.5")
    ap.add_argument("--radius", type=float, default=40.0)
    ap.add_argument("--prepare-only", action="store_true", help="write the grids and cases, run nothing")
    ap.add_argument("--report-only", action="store_true", help="only the table of the recorded runs")
    args = ap.parse_args()
    case_dir = os.path.abspath(args.case_dir.rstrip("/"))
    case = os.path.basename(case_dir)
    work = os.path.abspath(args.work)
    levels = [float(v) for v in args.talus_levels.split(",")]
    gc_levels = [float(v) for v in args.geoclaw_levels.split(",")]
    # accuracy, not timing: no waiting for a quiet machine before each run (peers_run.wait_quiet)
    os.environ.setdefault("PEERS_QUIET_WAIT", "0")
    if args.prepare_only:
        prepare(case_dir, work, case, levels, gc_levels, args.radius)
        return
    if not args.report_only:
        for var in ("TALUS_BIN", "GEOCLAW_EXE"):
            if not os.environ.get(var):
                sys.exit(f"dem_study: {var} is not set (run it through geoclaw_compare.sh --only setup,dem)")
        prepare(case_dir, work, case, levels, gc_levels, args.radius)
        done = {(r["key"], r["rep"]) for r in peers_run.load_records(work) if r.get("rc") == 0}
        # coarse to fine, GeoClaw beside Talus on each grid (resumable: a recorded run is not repeated)
        for res in sorted(set(levels) | set(gc_levels), reverse=True):
            name = case + "_r" + gc.res_name(res)
            jobs = []
            if res in levels:
                jobs.append(peers_run.talus_job(work, name, peers_run.GRID_TALUS_CONFIG, 2,
                                                os.path.join(work, "grids", name, "talus.run")))
            if res in gc_levels:
                jobs.append(peers_run.geoclaw_job(work, name, 2))
            for job in jobs:
                if (job["key"], 0) not in done:
                    peers_run.run_job(work, job, 0)
    report(work, case, levels, gc_levels)


if __name__ == "__main__":
    main()
