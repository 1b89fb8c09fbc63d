#!/usr/bin/env python3
"""What the affected-area difference between Talus and com1DFA is made of (issue 13, item 5).

  terrain_area_budget.py WORK CASE [RUN ...] [--data DATA] [--direction-from JSON] [--png DIR]
                        [--md FILE] [--label LABEL ...]

Run with a python that has numpy, scipy and rasterio (e.g. /work/avaframe-venv/bin/python).
WORK is a terrain_avaframe.sh work folder (WORK/avaframe/CASE with com1DFA's results,
WORK/talus/CASE/out*); RUN are Talus output folders (default: every WORK/talus/CASE/out*). A RUN may
be on another grid (the resampled DEMs of terrain_resample.py): its DEM is read from its
run.resolved.run, its areas and peak thickness are taken on its own grid, and for the Jaccard index
and the cell budget its slope-normal peak thickness is averaged onto the 5 m grid of DATA/CASE/dem.tif.

Prints a JSON list, com1DFA first and then one object per run; --md appends one Markdown row per run
(the table of docs/terrain_comparison.md, "what the area difference is made of"); --png maps:
  area_<t>       planimetric area with peak slope-normal thickness > t, t = 0.01, 0.1, 0.5, 1 m, for
                 com1DFA (pft) and Talus (hsmax * cos theta), and the Jaccard index at each t
  extra / missing  at 0.1 m: Talus-only / com1DFA-only area, split (a) by the thickness of the code
                 that has it (0.1-0.5 m "thin", > 0.5 m "core"), (b) by the other code's peak thickness
                 there (> 0.01 m: it passed there too, thinner), (c) by the distance to the other code's
                 0.1 m footprint (<= 10 m: a margin of 1-2 cells; > 30 m: far), and (d) by the along-flow coordinate
                 s (projection from the release centroid onto the flow direction, 250 m bins) and side
                 (left / right of that direction, looking downstream); and the Talus-only area that
                 Talus reached only after com1DFA's stop time (from tarrival.tif, 5 m runs)
  tent_*         area > 0.1 m and peak of the peak-thickness map after one bilinear tent pass (1/4 1/2 1/4
                 in x and y: com1DFA's particle -> mesh smoothing, interpOption = 2)
  peak           peak thickness, its s, and whether it lies in the release area; p99 of the peak
                 thickness over the affected cells
  area_0.1_by_s  the area > 0.1 m (on the reference grid) in 250 m bins of s: where along the path
                 the footprints differ
  runout         largest s of an affected cell (the flow direction from --direction-from, default
                 /work/terrain_peers/comparison.json, the one of docs/terrain_comparison.md's tables;
                 else release centroid -> com1DFA's affected centroid)
"""
import argparse
import glob
import json
import math
import pathlib
import sys

import numpy as np
import rasterio
from rasterio.warp import Resampling, reproject
from scipy import ndimage

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from terrain_compare import first, on_grid, read, slope_cos  # noqa: E402

THRESHOLDS = (0.01, 0.1, 0.5, 1.0)


def run_dem(tdir):
    for line in (tdir / "run.resolved.run").read_text().splitlines():
        if line.startswith("DEM="):
            p = pathlib.Path(line[4:].strip())
            return p if p.is_absolute() else (tdir.parent / p)
    raise RuntimeError(f"no DEM in {tdir}/run.resolved.run")


def talus_on_grid(tdir, ref_prof, ref_shape):
    """Slope-normal peak thickness of a Talus run on its own grid (with its cell) and on the reference grid."""
    rdem, _, rtr = read(run_dem(tdir))
    cell = abs(rtr.a)
    with rasterio.open(tdir / "hsmax.tif") as ds:
        hv = ds.read(1).astype(np.float64)
        src_tr, src_crs = ds.transform, ds.crs
    hn = np.nan_to_num(hv * slope_cos(rdem, cell), nan=0.0)
    if hn.shape == ref_shape and abs(cell - abs(ref_prof["transform"].a)) < 1e-6:
        return hn, cell, hn
    dst = np.zeros(ref_shape)
    reproject(hn, dst, src_transform=src_tr, src_crs=src_crs or ref_prof["crs"],
              dst_transform=ref_prof["transform"], dst_crs=ref_prof["crs"] or src_crs,
              resampling=Resampling.average)
    return hn, cell, dst


def budget(a, b, ha, hb, cell, s, side, tarr=None, tstop=None):
    """The cells in footprint b but not in footprint a (thicknesses hb, ha), described."""
    only = b & ~a
    c2 = cell * cell
    dist = ndimage.distance_transform_edt(~a) * cell  # distance to a's footprint
    r = {"m2": float(only.sum() * c2),
         "thin_0.1-0.5m_m2": float((only & (hb <= 0.5)).sum() * c2),
         "core_>0.5m_m2": float((only & (hb > 0.5)).sum() * c2),
         "core_>1m_m2": float((only & (hb > 1.0)).sum() * c2),
         "other_passed_>0.01m_m2": float((only & (ha > 0.01)).sum() * c2),
         "within_10m_of_other_m2": float((only & (dist <= 10.0 + 1e-9)).sum() * c2),
         "farther_than_30m_m2": float((only & (dist > 30.0)).sum() * c2),
         "sum_peak_thickness_dA_m3": float((hb * only).sum() * c2),
         "left_m2": float((only & (side > 0)).sum() * c2),
         "right_m2": float((only & (side <= 0)).sum() * c2)}
    if tarr is not None and tstop is not None:
        r[f"reached_after_{tstop:g}s_m2"] = float((only & (tarr > tstop)).sum() * c2)
    bins = {}
    for lo in range(-500, 3000, 250):
        m = only & (s >= lo) & (s < lo + 250)
        if m.any():
            bins[f"{lo}..{lo + 250}"] = float(m.sum() * c2)
    r["by_s_m2"] = bins
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("work", type=pathlib.Path)
    ap.add_argument("case")
    ap.add_argument("runs", nargs="*", type=pathlib.Path)
    ap.add_argument("--data", type=pathlib.Path, default=pathlib.Path("/work/shared/data/terrain"))
    ap.add_argument("--direction-from", type=pathlib.Path, default=pathlib.Path("/work/terrain_peers/comparison.json"))
    ap.add_argument("--png", type=pathlib.Path, help="write a map of both / Talus only / com1DFA only per run")
    ap.add_argument("--md", type=pathlib.Path, help="append one Markdown table row per run to this file")
    ap.add_argument("--label", action="append", default=[], help="row label per RUN, in order (default: folder name)")
    a = ap.parse_args()
    case = a.case
    dem, prof, tr = read(a.data / case / "dem.tif")
    rel = np.nan_to_num(read(a.data / case / "release.tif")[0], nan=0.0)
    cell = abs(tr.a)
    nr, nc = dem.shape
    rows, cols = np.mgrid[0:nr, 0:nc]
    x = tr.c + (cols + 0.5) * tr.a
    y = tr.f + (rows + 0.5) * tr.e
    relm = rel > 0
    xc, yc = x[relm].mean(), y[relm].mean()
    pk = a.work / "avaframe" / case / "Outputs" / "com1DFA" / "peakFiles"
    pft = np.nan_to_num(on_grid(read(first(str(pk / "*_pft.tif")))[0], dem.shape), nan=0.0)
    aff_a = pft > 0.1
    ts = sorted(glob.glob(str(pk / "timeSteps" / "*_pft_t*.tif")))
    t_a = float(ts[-1].rsplit("_t", 1)[1][:-4]) if ts else None  # com1DFA's stop time
    direction = None
    if a.direction_from.exists():
        direction = json.loads(a.direction_from.read_text()).get(case, {}).get("direction")
    if direction is None:
        dx, dy = x[aff_a].mean() - xc, y[aff_a].mean() - yc
        direction = (dx / math.hypot(dx, dy), dy / math.hypot(dx, dy))
    ex, ey = direction
    s = (x - xc) * ex + (y - yc) * ey
    side = -(x - xc) * ey + (y - yc) * ex  # > 0: left of the flow direction, looking downstream
    c2 = cell * cell

    def describe(h, hcell, hgrid, name):
        own = {f"area_{t}_m2": float((h > t).sum() * hcell * hcell) for t in THRESHOLDS}
        aff = hgrid > 0.1
        ipk = np.unravel_index(np.argmax(hgrid), hgrid.shape)
        # the same field after one bilinear-tent pass (weights 1/4 1/2 1/4 in x and y), as com1DFA's
        # particle -> mesh thickness (interpOption = 2) smooths; an upper bound for max_t of the
        # smoothed thickness since tent(max_t h) >= max_t tent(h)
        k = np.array([0.25, 0.5, 0.25])
        tent = ndimage.convolve1d(ndimage.convolve1d(hgrid, k, axis=0, mode="constant"), k, axis=1, mode="constant")
        d = {"run": name, "cell_m": hcell, **own,
             "tent_area_0.1_m2": float((tent > 0.1).sum() * c2), "tent_peak_m": float(tent.max()),
             "peak_m": float(h.max()), "peak_on_ref_grid_m": float(hgrid.max()),
             "peak_s_m": float(s[ipk]), "peak_in_release": bool(relm[ipk]),
             "p99_affected_m": float(np.percentile(hgrid[aff], 99)),
             "runout_m": float(np.where(aff, s, -np.inf).max())}
        d["area_0.1_by_s_m2"] = {f"{lo}..{lo + 250}": float((aff & (s >= lo) & (s < lo + 250)).sum() * c2)
                                 for lo in range(-250, 2500, 250)}
        return d

    out = [describe(pft, cell, pft, "com1DFA")]
    runs = a.runs or sorted(p for p in (a.work / "talus" / case).glob("out*") if (p / "hsmax.tif").exists())
    for tdir in runs:
        hn, hcell, hg = talus_on_grid(tdir, prof, dem.shape)
        d = describe(hn, hcell, hg, str(tdir))
        sj = json.loads((tdir / "summary.json").read_text())
        d["simulated_s"] = sj.get("simulated_s")
        d["status"] = sj.get("status")
        d["wall_s"] = sj.get("wall_time_s")
        for t in THRESHOLDS:
            A, B = pft > t, hg > t
            d[f"jaccard_{t}"] = float((A & B).sum() / max(1, (A | B).sum()))
        A, B = pft > 0.1, hg > 0.1
        tarr = None
        if (tdir / "tarrival.tif").exists() and hcell == cell:
            tarr = read(tdir / "tarrival.tif")[0]
            d["area_reached_after_com1DFA_stop_m2"] = float((B & (tarr > t_a)).sum() * c2)
        d["extra"] = budget(A, B, pft, hg, cell, s, side, tarr=tarr, tstop=t_a)
        d["missing"] = budget(B, A, hg, pft, cell, s, side)
        out.append(d)
        if a.png:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            a.png.mkdir(parents=True, exist_ok=True)
            cat = np.zeros(dem.shape)
            cat[A & B] = 1
            cat[B & ~A] = 2
            cat[A & ~B] = 3
            gy, gx = np.gradient(np.nan_to_num(dem, nan=np.nanmean(dem)), cell)
            shade = (gx - gy) / np.sqrt(1 + gx * gx + gy * gy)
            fig, ax = plt.subplots(figsize=(8, 8))
            ext = (x.min(), x.max(), y.min(), y.max())
            ax.imshow(shade, cmap="gray", extent=ext, alpha=0.6)
            from matplotlib.colors import ListedColormap
            ax.imshow(np.ma.masked_equal(cat, 0), cmap=ListedColormap(["#999999", "#d62728", "#1f77b4"]),
                      vmin=1, vmax=3, extent=ext, interpolation="nearest")
            ax.contour(x, y, relm.astype(float), [0.5], colors="k", linewidths=0.8)
            ax.set_title(f"{case} {tdir.parent.name}/{tdir.name}: grey both, red Talus only, blue com1DFA only (> 0.1 m)")
            ax.arrow(xc, yc, 300 * ex, 300 * ey, width=8, color="k")
            fig.savefig(a.png / f"{case}_{tdir.parent.name}_{tdir.name}.png", dpi=90, bbox_inches="tight")
            plt.close(fig)
    print(json.dumps(out, indent=1))
    if a.md:
        ref = out[0]
        labels = ["com1DFA"] + [a.label[i] if i < len(a.label) else pathlib.Path(r["run"]).name
                                for i, r in enumerate(out[1:])]
        with open(a.md, "a") as f:
            for lab, r in zip(labels, out):
                if lab == "com1DFA" and r is not ref:
                    continue
                ratio = lambda k: "" if r is ref else f" (x{r[k] / ref[k]:.2f})"
                n = lambda k: f"{r[k]:,.0f}".replace(",", " ") + ("" if k == "area_0.01_m2" else ratio(k))
                t_end = t_a if r is ref else (r.get("simulated_s") or 0)
                f.write(f"| {case} | {lab} | {r['cell_m']:.1f} | {t_end:.1f} | {n('area_0.01_m2')} | {n('area_0.1_m2')} | "
                        f"{n('area_0.5_m2')} | {n('area_1.0_m2')} | {r['peak_m']:.2f} / {r['tent_peak_m']:.2f} | "
                        f"{r['runout_m']:.0f} | {'' if r is ref else format(r['jaccard_0.1'], '.3f')} |\n")


if __name__ == "__main__":
    sys.exit(main())
