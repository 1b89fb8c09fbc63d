#!/usr/bin/env python3
"""A terrain case's Talus input on another cell size (issue 13, item 5: does the affected area converge?).

  terrain_resample.py CASE_DIR TALUS_CASE_DIR OUT_DIR --cell 10

Run with a python that has GDAL (e.g. /work/clawpack-venv/bin/python). CASE_DIR holds dem.tif;
TALUS_CASE_DIR is what `terrain_compare.py prep` wrote for that case (case.run, solids_vertical.tif).
Writes OUT_DIR/dem.tif (bilinear from dem.tif), OUT_DIR/solids_vertical.tif and OUT_DIR/case.run
(TALUS_CASE_DIR/case.run with DEM=dem.tif). The grid keeps the upper-left corner of dem.tif and
covers its extent (the last row / column may stick out by less than a cell). The vertical release
thickness is averaged onto the new grid (a coarser cell: the mean of the cells it covers; a finer
cell: its parent's value) and then scaled so that sum(h dx dy) equals the 5 m release volume exactly.
Prints the volumes and the scale factor as JSON.
"""
import argparse
import json
import math
import pathlib
import re
import sys

import numpy as np
from osgeo import gdal

gdal.UseExceptions()


def warp(src, dst, cell, alg, nodata=None):
    ds = gdal.Open(str(src))
    gt = ds.GetGeoTransform()
    x0, y1 = gt[0], gt[3]
    x1 = x0 + gt[1] * ds.RasterXSize
    y0 = y1 + gt[5] * ds.RasterYSize
    nx = math.ceil((x1 - x0) / cell - 1e-6)
    ny = math.ceil((y1 - y0) / cell - 1e-6)
    opts = gdal.WarpOptions(outputBounds=(x0, y1 - ny * cell, x0 + nx * cell, y1), xRes=cell, yRes=cell,
                            resampleAlg=alg, format="GTiff", creationOptions=["COMPRESS=DEFLATE"],
                            outputType=gdal.GDT_Float32, **({"dstNodata": nodata} if nodata is not None else {}))
    gdal.Warp(str(dst), ds, options=opts)
    return gt


def volume(path):
    ds = gdal.Open(str(path))
    a = ds.GetRasterBand(1).ReadAsArray().astype(np.float64)
    gt = ds.GetGeoTransform()
    return float(np.nansum(a) * abs(gt[1] * gt[5])), ds


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case_dir", type=pathlib.Path)
    ap.add_argument("talus_case_dir", type=pathlib.Path)
    ap.add_argument("out_dir", type=pathlib.Path)
    ap.add_argument("--cell", type=float, required=True)
    a = ap.parse_args()
    out = a.out_dir.resolve()
    out.mkdir(parents=True, exist_ok=True)
    src = gdal.Open(str(a.case_dir / "dem.tif"))  # kept open while its band is used
    dem_nod = src.GetRasterBand(1).GetNoDataValue()
    src = None
    warp(a.case_dir / "dem.tif", out / "dem.tif", a.cell, "bilinear", dem_nod)
    warp(a.talus_case_dir / "solids_vertical.tif", out / "solids_vertical.tif", a.cell, "average")
    v0, _ = volume(a.talus_case_dir / "solids_vertical.tif")
    v1, ds = volume(out / "solids_vertical.tif")
    h = np.nan_to_num(ds.GetRasterBand(1).ReadAsArray().astype(np.float64), nan=0.0)
    ds = None
    k = v0 / v1
    ds = gdal.Open(str(out / "solids_vertical.tif"), gdal.GA_Update)
    ds.GetRasterBand(1).WriteArray((h * k).astype(np.float32))
    ds = None
    v2, _ = volume(out / "solids_vertical.tif")
    run = (a.talus_case_dir / "case.run").read_text()
    run = re.sub(r"(?m)^DEM=.*$", "DEM=dem.tif", run)
    run = run.replace("[Input]", f"# Resampled to {a.cell:g} m by tools/peers/terrain_resample.py (bilinear DEM, "
                      f"release volume kept: x{k:.6f}).\n[Input]", 1)
    (out / "case.run").write_text(run)
    print(json.dumps({"cell_m": a.cell, "volume_5m_m3": v0, "volume_resampled_raw_m3": v1, "scale": k,
                      "volume_written_m3": v2, "out": str(out)}))


if __name__ == "__main__":
    sys.exit(main())
