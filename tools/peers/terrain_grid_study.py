#!/usr/bin/env python3
"""com1DFA's and Talus' grid dependence on the terrain cases (issue 13, item 5).

  terrain_grid_study.py prep RES_DIR INPUT_DIR
  terrain_grid_study.py table WORK CASE [--ava-res DIR] [--md FILE] [--png DIR] [--json FILE]
  terrain_grid_study.py rerun AVA_DIR NEW_DIR --set KEY=VALUE [--set ...]

Run with the AvaFrame virtual environment's python (numpy, scipy, rasterio, matplotlib).

prep: RES_DIR is a folder written by terrain_resample.py (dem.tif, the bilinear DEM on the new grid,
  and solids_vertical.tif, the vertical release thickness averaged onto it with the 5 m volume kept).
  Writes INPUT_DIR/dem.tif (a copy) and INPUT_DIR/release.tif, the slope-normal release thickness
  com1DFA reads, h_n = h_v cos(theta), with cos(theta) from centred differences of that same DEM (the
  inverse of terrain_compare.py prep). Both codes then start from the same DEM and the same release.
  INPUT_DIR is a case folder for terrain_avaframe_run.py, which runs com1DFA with
  meshCellSize = the DEM's cell (no remeshing).

rerun: com1DFA again on the inputs of an avalanche folder written by terrain_avaframe_run.py, with its
  com1DFA_override.ini plus the given [GENERAL] keys (e.g. seed=54321: how much of a difference is the
  random particle seeding alone). NEW_DIR gets a copy of AVA_DIR/Inputs; wall time in run_info.json.

table: for CASE, com1DFA at 5 m (WORK/avaframe/CASE) and at the cells found as
  DIR/CASE_<r>m (default DIR = WORK/avaframe_res), Talus at 5 m (WORK/talus/CASE/out_stop) and at
  WORK/res/CASE_<r>m/out_stop. Per run, on its own grid: the planimetric area with slope-normal peak
  thickness > 0.01 / 0.1 / 0.5 / 1 m (com1DFA pft; Talus hsmax cos(theta) of its own DEM), the peak
  thickness, the runout (largest s of a cell > 0.1 m, s = projection of the cell centre from the 5 m
  release centroid onto the flow direction of --direction-from, default
  /work/terrain_peers/comparison.json, as in
  docs/terrain_comparison.md), and the area > 0.1 m beyond s = S_LOWER ("lower part": avaKot's slope
  north of the bend, avaAlr's fan). Jaccard indices of the > 0.1 m footprints:
    - com1DFA at r against com1DFA at 5 m, and Talus at r against com1DFA at 5 m: the r-grid thickness
      averaged onto the 5 m grid first (as terrain_area_budget.py does);
    - Talus at r against com1DFA at r: on their common grid, cell by cell.
  "narrow" = the part of the area > 0.1 m narrower than about 12.5 m (see narrow_area).
  "far" = area > 0.1 m more than 30 m from the reference footprint (com1DFA at 5 m, and com1DFA at
  the same r for Talus), on the 5 m grid / the common grid. Variants DIR/CASE_<r>m_<label> (rerun)
  are rows "com1DFA, <label>"; their "same cell" Jaccard index is against the default com1DFA run.
  --png: per case, com1DFA's footprints at each cell overlaid, Talus' next to them, and both codes at
  2.5 m (PNG/<case>_grid_study.png).
"""
import argparse
import json
import pathlib
import shutil
import sys

import numpy as np
import rasterio
from rasterio.warp import Resampling, reproject
from scipy import ndimage

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from terrain_compare import first, read, slope_cos  # noqa: E402

THRESHOLDS = (0.01, 0.1, 0.5, 1.0)
S_LOWER = {"avaKot": 500.0, "avaAlr": 1500.0}  # as in terrain_comparison.md's cell budget
FAR_M = 30.0


def prep(a):
    src = a.res_dir.resolve()
    out = a.input_dir.resolve()
    out.mkdir(parents=True, exist_ok=True)
    shutil.copy(src / "dem.tif", out / "dem.tif")
    dem, prof, tr = read(src / "dem.tif")
    hv, hprof, htr = read(src / "solids_vertical.tif")
    assert hv.shape == dem.shape and abs(htr.a - tr.a) < 1e-9 and abs(htr.c - tr.c) < 1e-6 and abs(htr.f - tr.f) < 1e-6
    cell = abs(tr.a)
    hv = np.nan_to_num(hv, nan=0.0)
    cth = np.nan_to_num(slope_cos(dem, cell), nan=1.0)
    hn = np.where(hv > 0, hv * cth, 0.0)
    p = dict(hprof)
    p.update(dtype="float32", nodata=None, compress="deflate")
    with rasterio.open(out / "release.tif", "w", **p) as ds:
        ds.write(hn.astype(np.float32), 1)
    c2 = cell * cell
    print(json.dumps({"input": str(out), "cell_m": cell, "release_cells": int((hn > 0).sum()),
                      "volume_vertical_m3": float(hv.sum() * c2),
                      "volume_normal_over_cos_m3": float((hn / cth).sum() * c2),
                      "sum_hn_dxdy_m3": float(hn.sum() * c2)}))


def rerun(a):
    import time
    src, new = a.ava_dir.resolve(), a.new_dir.resolve()
    if new.exists():
        shutil.rmtree(new)
    new.mkdir(parents=True)
    shutil.copytree(src / "Inputs", new / "Inputs", ignore=shutil.ignore_patterns("remeshedRasters"))
    ini = (src / "com1DFA_override.ini").read_text()
    extra = "".join(f"{kv.split('=', 1)[0].strip()} = {kv.split('=', 1)[1].strip()}\n" for kv in a.set)
    ini = ini.replace("[GENERAL]\n", "[GENERAL]\n" + extra, 1)
    (new / "com1DFA_override.ini").write_text(ini)
    from avaframe.com1DFA import com1DFA
    from avaframe.in3Utils import cfgUtils, logUtils
    cfgMain = cfgUtils.getGeneralConfig()
    cfgMain["MAIN"]["avalancheDir"] = str(new)
    cfgMain["MAIN"]["nCPU"] = "2"
    for k in ("savePlot", "createReport", "ReportDir", "showPlot"):
        cfgMain["FLAGS"][k] = "False"
    logUtils.initiateLogger(str(new), "runCom1DFA_rerun")
    cfg = cfgUtils.getModuleConfig(com1DFA, str(new), fileOverride=new / "com1DFA_override.ini", toPrint=False)
    t0 = time.time()
    com1DFA.com1DFAMain(cfgMain, cfgInfo=cfg)
    info = json.loads((src / "run_info.json").read_text())
    info.update(avalancheDir=str(new), wall_s=time.time() - t0, rerun_of=str(src), extra_keys=a.set)
    (new / "run_info.json").write_text(json.dumps(info, indent=2))
    print(json.dumps(info, indent=2))


def com1dfa_peak(ava_dir):
    pk = ava_dir / "Outputs" / "com1DFA" / "peakFiles"
    pft, _, tr = read(first(str(pk / "*_pft.tif")))
    ts = sorted(pk.glob("timeSteps/*_pft_t*.tif"), key=lambda p: float(p.stem.rsplit("_t", 1)[1]))
    t_end = float(ts[-1].stem.rsplit("_t", 1)[1]) if ts else None
    info = json.loads((ava_dir / "run_info.json").read_text())
    return np.nan_to_num(pft, nan=0.0), t_end, info


def talus_peak(tdir):
    for line in (tdir / "run.resolved.run").read_text().splitlines():
        if line.startswith("DEM="):
            p = pathlib.Path(line[4:].strip())
            demp = p if p.is_absolute() else tdir.parent / p
    dem, _, tr = read(demp)
    hv, _, htr = read(tdir / "hsmax.tif")
    hn = np.nan_to_num(hv * slope_cos(dem, abs(tr.a)), nan=0.0)
    sj = json.loads((tdir / "summary.json").read_text())
    return hn, sj.get("simulated_s"), sj


def to_grid(h, tr, shape, ref_tr, crs):
    if h.shape == shape and abs(tr.a - ref_tr.a) < 1e-9:
        return h
    dst = np.zeros(shape)
    reproject(h, dst, src_transform=tr, src_crs=crs, dst_transform=ref_tr, dst_crs=crs,
              resampling=Resampling.average)
    return dst


def coords(tr, shape):
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    return tr.c + (cols + 0.5) * tr.a, tr.f + (rows + 0.5) * tr.e


def narrow_area(aff, cell, fine=2.5, radius_cells=2):
    """Area of footprint aff (own grid) that an opening with a disc of diameter (2 radius_cells + 1) fine
    = 12.5 m, on a fine-m grid (aff repeated onto it), removes: strips narrower than about 12.5 m,
    e.g. the tracks of single particles."""
    k = max(1, int(round(cell / fine)))
    f = np.kron(aff, np.ones((k, k), dtype=bool)) if k > 1 else aff
    yy, xx = np.mgrid[-radius_cells:radius_cells + 1, -radius_cells:radius_cells + 1]
    disc = xx * xx + yy * yy <= radius_cells * radius_cells
    opened = ndimage.binary_opening(f, structure=disc)
    return float((f & ~opened).sum() * (cell / k) ** 2)


def jaccard(A, B):
    return float((A & B).sum() / max(1, (A | B).sum()))


def far_area(B, A, cell):
    """Area of footprint B farther than FAR_M from footprint A (same grid)."""
    d = ndimage.distance_transform_edt(~A) * cell
    return float((B & (d > FAR_M)).sum() * cell * cell)


def table(a):
    work = a.work.resolve()
    case = a.case
    ava_res = (a.ava_res or work / "avaframe_res").resolve()
    dem5, prof5, tr5 = read(a.data / case / "dem.tif")
    crs = prof5["crs"]
    rel5 = np.nan_to_num(read(a.data / case / "release.tif")[0], nan=0.0) > 0
    x5, y5 = coords(tr5, dem5.shape)
    xc, yc = x5[rel5].mean(), y5[rel5].mean()
    ex, ey = json.loads(a.direction_from.read_text())[case]["direction"]
    s_low = S_LOWER.get(case, 0.0)

    runs = []  # (code, r label, cell, h, transform, t_end, wall, dem)
    cells = ["10", "5", "2.5"]
    for r in cells:
        if r == "5":
            ad, td = work / "avaframe" / case, work / "talus" / case / "out_stop"
        else:
            ad, td = ava_res / f"{case}_{r}m", work / "res" / f"{case}_{r}m" / "out_stop"
        if (ad / "run_info.json").exists():
            h, t_end, info = com1dfa_peak(ad)
            tr = read(ad / "Inputs" / "dem.tif")[2]
            runs.append(dict(code="com1DFA", r=r, h=h, tr=tr, t_end=t_end, wall=info.get("wall_s"), dir=str(ad)))
        if (td / "hsmax.tif").exists():
            h, t_end, sj = talus_peak(td)
            tr = read(td / "hsmax.tif")[2]
            runs.append(dict(code="Talus", r=r, h=h, tr=tr, t_end=t_end, wall=sj.get("wall_time_s"), dir=str(td)))

    for r in cells:  # com1DFA variants (terrain_grid_study.py rerun): DIR/CASE_<r>m_<variant>
        for ad in sorted(ava_res.glob(f"{case}_{r}m_*")):
            if (ad / "run_info.json").exists():
                h, t_end, info = com1dfa_peak(ad)
                runs.append(dict(code=f"com1DFA, {ad.name.split('m_', 1)[1]}", r=r, h=h,
                                 tr=read(ad / "Inputs" / "dem.tif")[2], t_end=t_end, wall=info.get("wall_s"), dir=str(ad)))

    ref5 = next(d for d in runs if d["code"] == "com1DFA" and d["r"] == "5")
    A5 = to_grid(ref5["h"], ref5["tr"], dem5.shape, tr5, crs) > 0.1
    out = []
    for d in runs:
        h, tr = d["h"], d["tr"]
        cell = abs(tr.a)
        x, y = coords(tr, h.shape)
        s = (x - xc) * ex + (y - yc) * ey
        aff = h > 0.1
        hg5 = to_grid(h, tr, dem5.shape, tr5, crs)
        B5 = hg5 > 0.1
        row = {"case": case, "code": d["code"], "cell": d["r"], "cell_m": cell, "dir": d["dir"],
               "end_s": d["t_end"], "wall_s": d["wall"],
               **{f"area_{t}_m2": float((h > t).sum() * cell * cell) for t in THRESHOLDS},
               "peak_m": float(h.max()),
               "runout_m": float(np.where(aff, s, -np.inf).max()),
               "lower_area_0.1_m2": float((aff & (s >= s_low)).sum() * cell * cell),
               "narrow_area_0.1_m2": narrow_area(aff, cell),
               "jaccard_vs_com1DFA_5m": jaccard(A5, B5),
               "far_from_com1DFA_5m_m2": far_area(B5, A5, abs(tr5.a))}
        same = next((e for e in runs if e["code"] == "com1DFA" and e["r"] == d["r"]), None)
        if d["code"] != "com1DFA" and same is not None:
            assert same["h"].shape == h.shape
            A = same["h"] > 0.1
            row["jaccard_vs_com1DFA_same_cell"] = jaccard(A, aff)
            row["far_from_com1DFA_same_cell_m2"] = far_area(aff, A, cell)
            row["only_vs_com1DFA_same_cell_m2"] = float((aff & ~A).sum() * cell * cell)
            # of this run's area far from com1DFA at 5 m, the part com1DFA at the same cell covers too
            far5 = B5 & (ndimage.distance_transform_edt(~A5) * abs(tr5.a) > FAR_M)
            As5 = to_grid(same["h"], same["tr"], dem5.shape, tr5, crs) > 0.1
            row["far_from_com1DFA_5m_also_com1DFA_same_cell_m2"] = float((far5 & As5).sum() * abs(tr5.a) ** 2)
        out.append(row)

    if a.json:
        a.json.write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))
    if a.md:
        fmt = lambda v: f"{v:,.0f}".replace(",", " ")
        ref = next(e for e in out if e["code"] == "com1DFA" and e["cell"] == "5")
        order = lambda e: (e["code"] == "Talus", e["code"] != "com1DFA", e["code"], -e["cell_m"])
        with open(a.md, "a") as f:
            for row in sorted(out, key=order):
                label = row["code"].replace("seed", "seed ").replace(
                    "dtcsz", f"dt = {0.02 * row['cell_m']:.2g} s")
                ratio = "" if row is ref else f" (×{row['area_0.1_m2'] / ref['area_0.1_m2']:.2f})"
                js = row.get("jaccard_vs_com1DFA_same_cell")
                wall = "" if row["wall_s"] is None else f"{row['wall_s']:.0f}"
                f.write(f"| {case} | {label} | {row['cell_m']:.1f} | {row['end_s']:.1f} | {wall} | "
                        f"{fmt(row['area_0.01_m2'])} | {fmt(row['area_0.1_m2'])}{ratio} | {fmt(row['area_0.5_m2'])} | "
                        f"{fmt(row['area_1.0_m2'])} | {row['peak_m']:.2f} | {row['runout_m']:.0f} | "
                        f"{fmt(row['lower_area_0.1_m2'])} | {fmt(row['narrow_area_0.1_m2'])} | "
                        f"{'' if row is ref else format(row['jaccard_vs_com1DFA_5m'], '.3f')} | "
                        f"{'' if row is ref else fmt(row['far_from_com1DFA_5m_m2'])} | "
                        f"{'' if js is None else format(js, '.3f')} |\n")
    if a.png:
        png(a, case, runs, dem5, tr5, rel5, xc, yc, ex, ey)


def png(a, case, runs, dem5, tr5, rel5, xc, yc, ex, ey):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D
    a.png.mkdir(parents=True, exist_ok=True)
    cell5 = abs(tr5.a)
    x5, y5 = coords(tr5, dem5.shape)
    gy, gx = np.gradient(np.nan_to_num(dem5, nan=np.nanmean(dem5)), cell5)
    shade = (gx - gy) / np.sqrt(1 + gx * gx + gy * gy)
    ext5 = (tr5.c, tr5.c + tr5.a * dem5.shape[1], tr5.f + tr5.e * dem5.shape[0], tr5.f)
    colors = {"10": "#1f77b4", "5": "#2ca02c", "2.5": "#d62728"}
    get = lambda code, r: next((e for e in runs if e["code"] == code and e["r"] == r), None)

    def draw(ax, d, color, fill=True):
        h, tr = d["h"], d["tr"]
        ext = (tr.c, tr.c + tr.a * h.shape[1], tr.f + tr.e * h.shape[0], tr.f)
        if fill:
            ax.imshow(np.ma.masked_equal((h > 0.1).astype(float), 0), cmap=ListedColormap([color]), alpha=0.3,
                      extent=ext, interpolation="nearest")
        x, y = coords(tr, h.shape)
        ax.contour(x, y, (h > 0.1).astype(float), [0.5], colors=color, linewidths=0.9)

    panels = [("com1DFA", [(get("com1DFA", r), colors[r], f"com1DFA {r} m") for r in ("10", "5", "2.5")]),
              ("Talus", [(get("Talus", r), colors[r], f"Talus {r} m") for r in ("10", "5", "2.5")]),
              ("both at 2.5 m", [(get("com1DFA", "2.5"), "#d62728", "com1DFA 2.5 m"),
                                 (get("Talus", "2.5"), "#1f77b4", "Talus 2.5 m")])]
    # the extent of all footprints, with a margin
    xs, ys = [], []
    for d in runs:
        x, y = coords(d["tr"], d["h"].shape)
        m = d["h"] > 0.1
        xs += [x[m].min(), x[m].max()]
        ys += [y[m].min(), y[m].max()]
    box = (min(xs) - 150, max(xs) + 150, min(ys) - 150, max(ys) + 150)
    fig, axes = plt.subplots(1, 3, figsize=(19, 9), sharex=True, sharey=True)
    for ax, (title, items) in zip(axes, panels):
        ax.imshow(shade, cmap="gray", extent=ext5, alpha=0.6)
        handles = []
        for d, color, label in items:
            if d is None:
                continue
            draw(ax, d, color)
            handles.append(Line2D([], [], color=color, label=label))
        ax.contour(x5, y5, rel5.astype(float), [0.5], colors="k", linewidths=0.8)
        ax.arrow(xc, yc, 300 * ex, 300 * ey, width=8, color="k")
        ax.set_title(f"{case}: {title}, peak thickness > 0.1 m")
        ax.legend(handles=handles, loc="lower right")
        ax.set_xlim(box[0], box[1])
        ax.set_ylim(box[2], box[3])
        ax.set_aspect("equal")
    fig.savefig(a.png / f"{case}_grid_study.png", dpi=80, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("prep")
    p.add_argument("res_dir", type=pathlib.Path)
    p.add_argument("input_dir", type=pathlib.Path)
    p.set_defaults(fn=prep)
    q = sub.add_parser("rerun")
    q.add_argument("ava_dir", type=pathlib.Path)
    q.add_argument("new_dir", type=pathlib.Path)
    q.add_argument("--set", action="append", default=[], help="KEY=VALUE for [GENERAL]")
    q.set_defaults(fn=rerun)
    t = sub.add_parser("table")
    t.add_argument("work", type=pathlib.Path)
    t.add_argument("case")
    t.add_argument("--ava-res", type=pathlib.Path)
    t.add_argument("--data", type=pathlib.Path, default=pathlib.Path("/work/shared/data/terrain"))
    t.add_argument("--direction-from", type=pathlib.Path, default=pathlib.Path("/work/terrain_peers/comparison.json"))
    t.add_argument("--md", type=pathlib.Path)
    t.add_argument("--png", type=pathlib.Path)
    t.add_argument("--json", type=pathlib.Path)
    t.set_defaults(fn=table)
    a = ap.parse_args()
    return a.fn(a)


if __name__ == "__main__":
    sys.exit(main())
