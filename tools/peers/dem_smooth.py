#!/usr/bin/env python3
"""A DEM smoothed by a Gaussian of given width, nodata kept (issue 13, item 5: how much of the
difference between two codes on a real DEM is how each feels its roughness at the scale of a cell).

  dem_smooth.py DEM_IN DEM_OUT --sigma-m 10

Normalised convolution: the valid cells' elevations and the valid mask are filtered alike and
divided, so nodata neither leaks into the border nor pulls it down. Run with a python that has
numpy, scipy and rasterio (e.g. the AvaFrame virtual environment's); prints the largest and the
rms change.
"""
import argparse

import numpy as np
import rasterio
from scipy import ndimage


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dem_in")
    ap.add_argument("dem_out")
    ap.add_argument("--sigma-m", type=float, default=10.0)
    a = ap.parse_args()
    with rasterio.open(a.dem_in) as ds:
        prof, z, nod = ds.profile, ds.read(1).astype(np.float64), ds.nodata
        cell = abs(ds.transform.a)
    valid = np.isfinite(z) if nod is None else (np.isfinite(z) & (z != nod))
    sigma = a.sigma_m / cell
    w = ndimage.gaussian_filter(valid.astype(np.float64), sigma, mode="constant")
    s = ndimage.gaussian_filter(np.where(valid, z, 0.0), sigma, mode="constant") / np.maximum(w, 1e-12)
    out = np.where(valid, s, z)
    prof.update(dtype="float64")
    with rasterio.open(a.dem_out, "w", **prof) as ds:
        ds.write(out, 1)
    d = (out - z)[valid]
    print(f"{a.dem_out}: sigma {a.sigma_m:g} m, largest change {np.abs(d).max():.2f} m, rms {np.sqrt((d * d).mean()):.2f} m")


if __name__ == "__main__":
    main()
