#!/usr/bin/env python3
"""Centroid travel of the deposit, Talus beside com1DFA (issue 13, item 5).

  terrain_centroid.py --release SOLIDS_VERTICAL.tif [--along ALONG.tif | --direction-from JSON CASE]
      [--reference M] RUN [RUN ...]
  RUN = LABEL=KIND:DEM:DIR   KIND talus (DIR = a Talus output folder: hsfinal.tif, vsmax.tif) or
                             com1dfa (DIR = an avalanche folder: Outputs/com1DFA/peakFiles/*_FT.tif,
                             *_pfv.tif); DEM = the DEM that run used (for cos(theta) and elevations)

The mass-weighted centroid of the release (vertical thickness) and of each run's final deposit
(Talus' vertical hsfinal; com1DFA's slope-normal FT over cos(theta) of DEM): its drop, its travel
and tan(alpha) = drop / travel, the travel angle of the centre of mass. For a Coulomb mass that
slides without curvature effects tan(alpha) is mu (the energy line); the bend's centripetal
friction adds to it. Travel: along the coordinate of --along (valley_scene.py's along.tif), or the
horizontal distance between the centroids. Also the runout of the final deposit (largest s of a
cell with slope-normal thickness > 0.1 m, s along --along or along the flow direction of
--direction-from's CASE measured from the release centroid), the affected area (planimetric, peak
slope-normal thickness > 0.1 m: hsmax cos(theta) / pft) and the peak speed (vsmax, Talus'
horizontal speed / pfv, com1DFA's speed along the bed).
--reference: a travel to compare with (e.g. the bead's, 690.4 m on the valley scene).
Run with the AvaFrame virtual environment's python (numpy, rasterio).
"""
import argparse
import json
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from terrain_compare import first, read, slope_cos  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--release", required=True)
    ap.add_argument("--along")
    ap.add_argument("--direction-from", nargs=2, metavar=("JSON", "CASE"))
    ap.add_argument("--reference", type=float)
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    rel, _, tr = read(a.release)
    rel = np.nan_to_num(rel)
    ny, nx = rel.shape
    X, Y = np.meshgrid(tr.c + tr.a * (np.arange(nx) + 0.5), tr.f + tr.e * (np.arange(ny) + 0.5))
    cell = abs(tr.a)
    c0 = np.array([(rel * X).sum(), (rel * Y).sum()]) / rel.sum()
    if a.along:
        S = np.nan_to_num(read(a.along)[0])
    elif a.direction_from:
        d = json.loads(pathlib.Path(a.direction_from[0]).read_text())[a.direction_from[1]]["direction"]
        S = (X - c0[0]) * d[0] + (Y - c0[1]) * d[1]
    else:
        sys.exit("terrain_centroid.py: give --along or --direction-from")
    print("| run | centroid drop [m] | centroid travel [m] | tan(alpha) | runout of the deposit [m] | affected area > 0.1 m [m²] | peak speed [m/s] |")
    print("|---|---|---|---|---|---|---|")
    for run in a.runs:
        label, spec = run.rsplit("=", 1)  # labels may hold "=" (run-file keys)
        kind, dem_path, folder = spec.split(":", 2)
        dem = read(dem_path)[0]
        cos = slope_cos(dem, cell)
        if kind == "talus":
            hv = np.nan_to_num(read(f"{folder}/hsfinal.tif")[0])
            v = np.nan_to_num(read(f"{folder}/vsmax.tif")[0])
            hn = hv * cos
            peak = np.nan_to_num(read(f"{folder}/hsmax.tif")[0]) * np.nan_to_num(cos)
        elif kind == "com1dfa":
            hn = np.nan_to_num(read(first(f"{folder}/Outputs/com1DFA/peakFiles/*_FT.tif"))[0])
            v = np.nan_to_num(read(first(f"{folder}/Outputs/com1DFA/peakFiles/*_pfv.tif"))[0])
            peak = np.nan_to_num(read(first(f"{folder}/Outputs/com1DFA/peakFiles/*_pft.tif"))[0])
            hv = hn / np.maximum(np.nan_to_num(cos), 1e-6)
        else:
            sys.exit(f"terrain_centroid.py: unknown kind '{kind}' in {run}")
        z = np.nan_to_num(dem)
        drop = (rel * z).sum() / rel.sum() - (hv * z).sum() / hv.sum()
        if a.along:
            travel = (hv * S).sum() / hv.sum() - (rel * S).sum() / rel.sum()
        else:
            c = np.array([(hv * X).sum(), (hv * Y).sum()]) / hv.sum()
            travel = float(np.hypot(*(c - c0)))
        ref = f" ({travel / a.reference - 1:+.1%})" if a.reference else ""
        area = f"{(peak > 0.1).sum() * cell * cell:,.0f}".replace(",", " ")
        runout = S[hn > 0.1].max() - (0.0 if not a.along else (rel * S).sum() / rel.sum())
        print(f"| {label} | {drop:.1f} | {travel:.1f}{ref} | {drop / travel:.3f} | {runout:.0f} | {area} | {v.max():.1f} |")


if __name__ == "__main__":
    main()
