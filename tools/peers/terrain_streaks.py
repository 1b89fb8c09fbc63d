#!/usr/bin/env python3
"""Thin features of the affected areas (peak thickness > 0.1 m) of the terrain runs, and a PNG.

    /work/avaframe-venv/bin/python tools/peers/terrain_streaks.py WORK_DIR CASE [--png FILE]
        [--extra LABEL=OUT_DIR ...] [--data DIR]

Runs: com1DFA (WORK_DIR/avaframe/<case>), every Talus WORK_DIR/talus/<case>/out*, and --extra Talus
output folders (e.g. of an earlier commit). A cell is "thin" when it is affected but no 3 x 3 block of
affected cells contains it (a feature 1-2 cells wide); a streak is a thin 8-connected component of at
least 5 cells whose length (largest extent) is at least 4 times its mean width (cells / length).
Printed per run: affected cells, thin cells, streaks (count, cells, longest [m], how many lie within
10 deg of a grid direction: 0/45/90/135 deg), and the peak speed (any thickness) against the
frictionless bound sqrt(2 g (z_top - z)) from the release's highest cell z_top: the cells above it more
than 10 m below z_top (within a few metres of z_top the release's own head, up to 2.8 m, dominates), and
the largest ratio speed / bound more than 50 m below z_top.
"""
import argparse
import math
import pathlib
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from terrain_compare import THRESH, first, on_grid, read, slope_cos  # noqa: E402


def streaks(aff, cell):
    opened = ndimage.binary_opening(aff, structure=np.ones((3, 3), bool))
    thin = aff & ~opened
    lab, n = ndimage.label(thin, structure=np.ones((3, 3), bool))
    out = []
    for i, sl in enumerate(ndimage.find_objects(lab), start=1):
        r, c = np.nonzero(lab[sl] == i)
        if r.size < 5:
            continue
        pts = np.c_[c, -r].astype(float)
        pts -= pts.mean(axis=0)
        w, v = np.linalg.eigh(pts.T @ pts)
        axis = v[:, 1]
        proj = pts @ axis
        length = proj.max() - proj.min() + 1
        if length < 4 * r.size / length:
            continue
        ang = math.degrees(math.atan2(axis[1], axis[0])) % 45.0
        out.append((r.size, length * cell, min(ang, 45.0 - ang) <= 10.0))
    return thin, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("work_dir", type=pathlib.Path)
    ap.add_argument("case")
    ap.add_argument("--data", default="/work/shared/data/terrain")
    ap.add_argument("--extra", action="append", default=[], help="LABEL=TALUS_OUT_DIR")
    ap.add_argument("--png")
    a = ap.parse_args()
    cdir = pathlib.Path(a.data) / a.case
    dem, _, tr = read(cdir / "dem.tif")
    cell = abs(tr.a)
    cth = slope_cos(dem, cell)
    rel = read(cdir / "release.tif")[0] > 0
    drop = np.nanmax(np.where(rel, dem, np.nan)) - dem
    bound = np.sqrt(2 * 9.81 * np.maximum(drop, 0))
    runs, speed = {}, {}
    pk = a.work_dir / "avaframe" / a.case / "Outputs" / "com1DFA" / "peakFiles"
    if pk.exists():
        runs["com1DFA"] = on_grid(read(first(str(pk / "*_pft.tif")))[0], dem.shape)
        speed["com1DFA"] = on_grid(read(first(str(pk / "*_pfv.tif")))[0], dem.shape)
    dirs = [(d.name[4:] or "Talus mc (default)", d) for d in sorted((a.work_dir / "talus" / a.case).glob("out*"))]
    dirs += [tuple(e.split("=", 1)) for e in a.extra]
    for label, d in dirs:
        if (pathlib.Path(d) / "hsmax.tif").exists():
            runs[label] = read(pathlib.Path(d) / "hsmax.tif")[0] * cth
            speed[label] = read(pathlib.Path(d) / "vsmax.tif")[0]
    print(f"| {a.case} run | affected cells | thin cells (1-2 wide) | streaks | streak cells | longest [m] | grid-aligned | above bound, drop > 10 m | max speed/bound, drop > 50 m |")
    print("|---|---|---|---|---|---|---|---|---|")
    masks = {}
    for label, h in runs.items():
        aff = np.nan_to_num(h, nan=0.0) > THRESH
        thin, st = streaks(aff, cell)
        masks[label] = (aff, thin)
        v = np.nan_to_num(speed[label], nan=0.0)
        ratio = np.where(drop > 50, v / np.where(drop > 50, bound, 1), 0)
        print(f"| {label} | {aff.sum()} | {thin.sum()} | {len(st)} | {sum(s[0] for s in st)} | "
              f"{max([s[1] for s in st], default=0):.0f} | {sum(s[2] for s in st)} | "
              f"{((v > bound) & (drop > 10)).sum()} | {np.nanmax(ratio):.2f} |")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        union = np.logical_or.reduce([m[0] for m in masks.values()])
        rr, cc = np.nonzero(union)
        r0, r1, c0, c1 = max(rr.min() - 10, 0), rr.max() + 11, max(cc.min() - 10, 0), cc.max() + 11
        gy, gx = np.gradient(np.nan_to_num(dem, nan=np.nanmean(dem)), cell)
        shade = (gx - gy) / np.sqrt(1 + gx * gx + gy * gy)
        n = len(masks)
        w = min(1.9, 3.6 * (c1 - c0) / (r1 - r0))  # panel width [in], panels at most 3.6 in tall
        fig, axs = plt.subplots(1, n, figsize=(w * n, w * (r1 - r0) / (c1 - c0) + 0.5), dpi=110)
        for ax, (label, (aff, thin)) in zip(np.atleast_1d(axs), masks.items()):
            ax.imshow(shade[r0:r1, c0:c1], cmap="gray", vmin=-1.5, vmax=1.5)
            rgba = np.zeros(aff[r0:r1, c0:c1].shape + (4,))
            rgba[aff[r0:r1, c0:c1]] = (0.1, 0.4, 0.9, 0.6)
            rgba[thin[r0:r1, c0:c1]] = (0.9, 0.1, 0.1, 1.0)
            ax.imshow(rgba, interpolation="nearest")
            ax.set_title(label, fontsize=7)
            ax.set_xticks([])
            ax.set_yticks([])
        fig.suptitle(f"{a.case}: peak thickness > {THRESH} m (blue), 1-2 cell wide parts (red); north up", fontsize=7)
        fig.tight_layout()
        fig.canvas.draw()
        from PIL import Image  # palette PNG keeps the file small
        Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3]).quantize(64).save(a.png, optimize=True)


if __name__ == "__main__":
    sys.exit(main())
