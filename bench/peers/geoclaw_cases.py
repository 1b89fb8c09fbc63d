#!/usr/bin/env python3
"""Input preparation for the Talus / GeoClaw side-by-side comparison (bench/peers/).

Sub-commands (all paths absolute or relative to the current directory):

  grids  REPO WORK [--levels 10,5,2.5]   derived kot_dambreak grids + Talus run-files + GeoClaw cases
  ritter WORK [--dx 1,0.5,0.25]          Ritter dam-break inputs for both codes

Layout written under WORK:

  grids/r<res>/dem.tif, water.tif, talus.run     the very same DEM and water for both codes
  geoclaw/kot_r<res>/*.data, topo.tt3, qinit.xyz GeoClaw data files (single level, no AMR)
  ritter/dx<dx>/...                              the same for the Ritter dam break

GeoClaw sees topography only through its cell averages of the piecewise-bilinear surface through
the topo file's nodes (setaux -> cellgridintegrate). With the nodes at the cell centres, the average
over a cell is (1/8, 3/4, 1/8) (x) (1/8, 3/4, 1/8) of the nodes around it, not the node value. We
therefore write node values N that solve that (diagonally dominant, well conditioned) separable
system exactly, so GeoClaw's cell averages equal the DEM cell values (to round-off). The initial
water is given the same way as a qinit file of type 4 (surface elevation eta, again cell-averaged by
GeoClaw), with eta = z + h on wet cells and eta = z - 10 m on dry ones, so h = max(eta - B, 0) is the
Talus water thickness to round-off.
"""
import argparse
import contextlib
import json
import math
import os
import subprocess
import tempfile

import numpy as np

NODATA = -9999.0
GRAVITY = 9.81
DRY3 = "__dry1e-3"  # suffix of the GeoClaw case folders with GeoClaw's default dry tolerance

# kot_dambreak water column (data/kot_dambreak/README.md)
DISC_X, DISC_Y, DISC_R, DISC_ETA = 177835.539, 376735.106, 40.0, 1959.83


# ----------------------------------------------------------------------------------------------
# Raster I/O: GDAL's Python bindings when present, otherwise gdal_translate through AAIGrid.
# ----------------------------------------------------------------------------------------------
try:
    from osgeo import gdal  # noqa: E402

    gdal.UseExceptions()
except Exception:  # pragma: no cover - depends on the machine
    gdal = None


class Raster:
    """A north-up grid: values (rows from the top, NaN = nodata) and its georeference."""

    def __init__(self, values, ulx, uly, dx, wkt=""):
        self.values = np.asarray(values, dtype=np.float64)
        self.ulx, self.uly, self.dx, self.wkt = float(ulx), float(uly), float(dx), wkt

    @property
    def ny(self):
        return self.values.shape[0]

    @property
    def nx(self):
        return self.values.shape[1]

    def centres(self):
        """World x (per column) and y (per row) of the cell centres."""
        x = self.ulx + (np.arange(self.nx) + 0.5) * self.dx
        y = self.uly - (np.arange(self.ny) + 0.5) * self.dx
        return x, y


def read_raster(path):
    if gdal is not None:
        ds = gdal.Open(str(path))
        band = ds.GetRasterBand(1)
        a = band.ReadAsArray().astype(np.float64)
        nd = band.GetNoDataValue()
        if nd is not None:
            a[a == nd] = np.nan
        gt = ds.GetGeoTransform()
        if abs(gt[2]) > 0 or abs(gt[4]) > 0 or abs(abs(gt[5]) - gt[1]) > 1e-9 * gt[1]:
            raise SystemExit(f"{path}: only north-up grids with square cells are supported")
        return Raster(a, gt[0], gt[3], gt[1], ds.GetProjection())
    with tempfile.TemporaryDirectory() as td:
        asc = os.path.join(td, "r.asc")
        subprocess.run(["gdal_translate", "-q", "-of", "AAIGrid", "-co", "SIGNIFICANT_DIGITS=17",
                        str(path), asc], check=True)
        return read_aaigrid(asc)


def read_aaigrid(path):
    head = {}
    with open(path) as f:
        for _ in range(6):
            pos = f.tell()
            line = f.readline().split()
            if not line or not line[0][0].isalpha():
                f.seek(pos)
                break
            head[line[0].lower()] = float(line[1])
        a = np.loadtxt(f, dtype=np.float64, ndmin=2)
    nd = head.get("nodata_value")
    if nd is not None:
        a[a == nd] = np.nan
    dx = head["cellsize"]
    ulx = head.get("xllcorner", head.get("xllcenter", 0.0) - 0.5 * dx)
    yll = head.get("yllcorner", head.get("yllcenter", 0.0) - 0.5 * dx)
    return Raster(a, ulx, yll + a.shape[0] * dx, dx)


def write_raster(path, raster, nodata=NODATA, srs=None):
    """Float32 GeoTIFF (deflate), NaN written as nodata."""
    a = np.where(np.isnan(raster.values), nodata, raster.values).astype(np.float32)
    path = str(path)
    if gdal is not None:
        drv = gdal.GetDriverByName("GTiff")
        ds = drv.Create(path, raster.nx, raster.ny, 1, gdal.GDT_Float32, options=["COMPRESS=DEFLATE"])
        ds.SetGeoTransform((raster.ulx, raster.dx, 0.0, raster.uly, 0.0, -raster.dx))
        if raster.wkt:
            ds.SetProjection(raster.wkt)
        band = ds.GetRasterBand(1)
        band.SetNoDataValue(nodata)
        band.WriteArray(a)
        band.FlushCache()
        ds = None
        return
    with tempfile.TemporaryDirectory() as td:
        asc = os.path.join(td, "r.asc")
        with open(asc, "w") as f:
            f.write(f"ncols {raster.nx}\nnrows {raster.ny}\n")
            f.write(f"xllcorner {raster.ulx!r}\nyllcorner {raster.uly - raster.ny * raster.dx!r}\n")
            f.write(f"cellsize {raster.dx!r}\nNODATA_value {nodata!r}\n")
            np.savetxt(f, a.astype(np.float64), fmt="%.9g")
        cmd = ["gdal_translate", "-q", "-of", "GTiff", "-ot", "Float32", "-co", "COMPRESS=DEFLATE"]
        if srs:
            cmd += ["-a_srs", srs]
        subprocess.run(cmd + [asc, path], check=True)


# ----------------------------------------------------------------------------------------------
# Grid derivation (grid study)
# ----------------------------------------------------------------------------------------------
def coarsen_mean(r, f):
    """Mean of f x f blocks; nodata where any cell of the block is nodata."""
    ny, nx = r.ny // f, r.nx // f
    a = r.values[: ny * f, : nx * f].reshape(ny, f, nx, f).mean(axis=(1, 3))  # NaN propagates
    return Raster(a, r.ulx, r.uly, r.dx * f, r.wkt)


def refine_bilinear(r, f):
    """Bilinear interpolation of the cell-centre values onto cells f times smaller.

    A fine cell is nodata exactly where its parent (the coarse cell containing it) is nodata, so
    the nodata mask is the same region at every resolution. Nodata neighbours and neighbours beyond
    the raster edge get zero weight (the remaining weights are renormalised), which is the same as
    extending the surface by its nearest valid value there.
    """
    ny, nx = r.ny * f, r.nx * f
    # fine cell centres in coarse-index units (coarse centre i sits at i)
    s = (np.arange(nx) + 0.5) / f - 0.5
    t = (np.arange(ny) + 0.5) / f - 0.5
    i0 = np.floor(s).astype(int)
    j0 = np.floor(t).astype(int)
    wx1 = s - i0
    wy1 = t - j0
    v = r.values
    valid = ~np.isnan(v)
    vz = np.where(valid, v, 0.0)
    num = np.zeros((ny, nx))
    den = np.zeros((ny, nx))
    for dj, wy in ((0, 1.0 - wy1), (1, wy1)):
        jj = j0 + dj
        jin = (jj >= 0) & (jj < r.ny)
        jc = np.clip(jj, 0, r.ny - 1)
        for di, wx in ((0, 1.0 - wx1), (1, wx1)):
            ii = i0 + di
            iin = (ii >= 0) & (ii < r.nx)
            ic = np.clip(ii, 0, r.nx - 1)
            w = np.outer(wy * jin, wx * iin) * valid[np.ix_(jc, ic)]
            num += w * vz[np.ix_(jc, ic)]
            den += w
    out = np.where(den > 0, num / np.where(den > 0, den, 1.0), np.nan)
    parent = np.repeat(np.repeat(valid, f, axis=0), f, axis=1)
    out[~parent] = np.nan
    return Raster(out, r.ulx, r.uly, r.dx / f, r.wkt)


def water_column(dem, cx=DISC_X, cy=DISC_Y, radius=DISC_R, eta=DISC_ETA):
    """h = max(0, eta - z) inside the disc of `radius` around (cx, cy), 0 elsewhere; by default
    kot_dambreak's column (1959.83 m, 40 m, the README's centre)."""
    x, y = dem.centres()
    d2 = (x[None, :] - cx) ** 2 + (y[:, None] - cy) ** 2
    z = dem.values
    h = np.where((d2 <= radius ** 2) & ~np.isnan(z), np.maximum(0.0, eta - np.nan_to_num(z)), 0.0)
    return Raster(h, dem.ulx, dem.uly, dem.dx, dem.wkt)


def f32(r):
    """Round to the Float32 values the GeoTIFF stores, so both codes read identical numbers."""
    return Raster(r.values.astype(np.float32).astype(np.float64), r.ulx, r.uly, r.dx, r.wkt)


def res_name(res):
    return ("%g" % res).replace(".", "p")


def talus_runfile(template_path, dem_name, water_name):
    out = []
    for line in open(template_path).read().splitlines():
        key = line.split("=", 1)[0].strip()
        if key == "DEM":
            line = "DEM=" + dem_name
        elif key == "Initial Fluid Height":
            line = "Initial Fluid Height=" + water_name
        elif key == "Map Directory":
            line = "Map Directory=."
        out.append(line)
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------------------------
# GeoClaw inputs: topo and qinit node values whose GeoClaw cell averages equal the target cells
# ----------------------------------------------------------------------------------------------
def _solve_1_6_1(target, axis):
    """Solve (N[i-1] + 6 N[i] + N[i+1]) / 8 = T[i] along axis (N[-1] := N[0], N[n] := N[n-1]).

    Only the closure rows 0 and n-1 are approximate; every interior row holds exactly.
    """
    T = np.moveaxis(np.asarray(target, dtype=np.float64), axis, 0)
    n = T.shape[0]
    a = c = 0.125
    b = np.full(n, 0.75)
    b[0] += 0.125
    b[-1] += 0.125
    cp = np.empty(n)
    dp = np.empty_like(T)
    cp[0] = c / b[0]
    dp[0] = T[0] / b[0]
    for i in range(1, n):
        m = b[i] - a * cp[i - 1]
        cp[i] = c / m
        dp[i] = (T[i] - a * dp[i - 1]) / m
    N = np.empty_like(T)
    N[-1] = dp[-1]
    for i in range(n - 2, -1, -1):
        N[i] = dp[i] - cp[i] * N[i + 1]
    return np.moveaxis(N, 0, axis)


def nodes_for_cell_averages(cells, margin=3):
    """Node values (cell centres, rows from the top, margin cells of edge-replicated padding on
    each side) whose piecewise-bilinear surface averages to `cells` over every cell of the grid."""
    T = np.pad(np.asarray(cells, dtype=np.float64), margin, mode="edge")
    return _solve_1_6_1(_solve_1_6_1(T, 1), 0)


def cell_averages_of_nodes(N):
    """Forward operator (for the self-check): GeoClaw's average of the bilinear surface."""
    def fwd(a, axis):
        a = np.moveaxis(a, axis, 0)
        o = a.copy()
        o[1:-1] = (a[:-2] + 6 * a[1:-1] + a[2:]) / 8
        return np.moveaxis(o, 0, axis)
    return fwd(fwd(N, 1), 0)


def write_tt3(path, N, dx, margin):
    """Topotype-3 file, nodes at the cell centres of a domain whose lower-left corner is (0, 0)."""
    ny, nx = N.shape
    xll = (0.5 - margin) * dx
    with open(path, "w") as f:
        f.write(f"{nx} ncols\n{ny} nrows\n{xll!r} xllcenter\n{xll!r} yllcenter\n{dx!r} cellsize\n"
                f"-1e30 nodata_value\n")
        np.savetxt(f, N, fmt="%.17g")


def write_qinit_xyz(path, N, dx, margin):
    """qinit file: 'x y value' per line from the north-west corner, across then down."""
    ny, nx = N.shape
    x = (np.arange(nx) + 0.5 - margin) * dx
    y = (ny - 1 - np.arange(ny) + 0.5 - margin) * dx
    X, Y = np.meshgrid(x, y)
    np.savetxt(path, np.column_stack([X.ravel(), Y.ravel(), N.ravel()]), fmt="%.17g")


def geoclaw_case(case_dir, z, h, dx, tfinal, nout, bc, manning, wall_height, out_format, fgmax,
                 dry_tolerance=1e-6, margin=3):
    """Write a complete single-level GeoClaw case (data files + topo + qinit) into case_dir.

    z, h: 2D arrays with rows from the top (north); z NaN = nodata -> wall of height wall_height.
    The domain is [0, nx dx] x [0, ny dx] (local coordinates; lower-left corner at the origin).
    """
    from clawpack.clawutil import data
    from clawpack.geoclaw import fgmax_tools

    os.makedirs(case_dir, exist_ok=True)
    ny, nx = z.shape
    zb = np.where(np.isnan(z), wall_height, z)
    eta = np.where(h > 0, zb + h, zb - 10.0)
    topo_path = os.path.join(case_dir, "topo.tt3")
    qinit_path = os.path.join(case_dir, "qinit.xyz")
    Nz = nodes_for_cell_averages(zb, margin)
    Ne = nodes_for_cell_averages(eta, margin)
    write_tt3(topo_path, Nz, dx, margin)
    write_qinit_xyz(qinit_path, Ne, dx, margin)
    # self-check of the construction (GeoClaw's own averages are checked after the run)
    chk = cell_averages_of_nodes(Nz)[margin:-margin, margin:-margin]
    np.save(os.path.join(case_dir, "target_topo.npy"), zb)
    np.save(os.path.join(case_dir, "target_h.npy"), h)

    rd = data.ClawRunData("geoclaw", 2)
    cd = rd.clawdata
    cd.num_dim = 2
    cd.lower[0], cd.upper[0] = 0.0, nx * dx
    cd.lower[1], cd.upper[1] = 0.0, ny * dx
    cd.num_cells[0], cd.num_cells[1] = nx, ny
    cd.num_eqn, cd.num_aux, cd.capa_index = 3, 1, 0
    cd.t0 = 0.0
    cd.restart = False
    cd.output_style = 1
    cd.num_output_times = nout
    cd.tfinal = tfinal
    cd.output_t0 = True
    cd.output_format = out_format
    cd.output_q_components = "all"
    cd.output_aux_components = "all"
    cd.output_aux_onlyonce = True
    cd.verbosity = 1  # one line per step: the step count is read from it
    # time stepping and method: GeoClaw's standard settings (not tuned)
    cd.dt_variable = True
    cd.dt_max = 1e99
    cd.cfl_desired = 0.75
    cd.cfl_max = 1.0
    cd.steps_max = 10 ** 7
    cd.order = 2
    cd.dimensional_split = "unsplit"
    cd.transverse_waves = 2
    cd.num_waves = 3
    cd.limiter = ["mc", "mc", "mc"]
    cd.use_fwaves = True
    cd.source_split = "godunov"
    cd.num_ghost = 2
    cd.bc_lower[0] = cd.bc_upper[0] = bc
    cd.bc_lower[1] = cd.bc_upper[1] = bc
    cd.checkpt_style = 0

    amr = rd.amrdata
    amr.amr_levels_max = 1  # single grid level, no refinement
    amr.refinement_ratios_x = [2]
    amr.refinement_ratios_y = [2]
    amr.refinement_ratios_t = [2]
    amr.aux_type = ["center"]
    amr.flag_richardson = False
    amr.flag2refine = True
    amr.regrid_interval = 3
    amr.regrid_buffer_width = 2
    amr.clustering_cutoff = 0.7
    amr.verbosity_regrid = 0

    rd.regiondata.regions = []
    rd.gaugedata.gauges = []

    geo = rd.geo_data
    geo.gravity = GRAVITY
    geo.coordinate_system = 1
    geo.earth_radius = 6367.5e3
    geo.coriolis_forcing = False
    geo.sea_level = 0.0  # every bed cell lies above it: the domain starts dry, water from qinit
    geo.dry_tolerance = dry_tolerance
    geo.friction_forcing = manning > 0
    geo.manning_coefficient = manning
    geo.friction_depth = 1e10  # friction at every depth
    rd.refinement_data.wave_tolerance = 0.1
    rd.refinement_data.variable_dt_refinement_ratios = False

    rd.topo_data.topofiles = [[3, topo_path]]
    rd.qinit_data.qinit_type = 4  # surface elevation eta; h = max(eta - B, 0)
    rd.qinit_data.qinitfiles = [[qinit_path]]

    rd.fgmax_data.num_fgmax_val = 1
    if fgmax:
        fg = fgmax_tools.FGmaxGrid()
        fg.point_style = 2
        fg.x1, fg.x2 = 0.5 * dx, (nx - 0.5) * dx
        fg.y1, fg.y2 = 0.5 * dx, (ny - 0.5) * dx
        fg.dx = dx
        fg.tstart_max = 0.0
        fg.tend_max = 1e10
        fg.dt_check = 0.0  # every step
        fg.min_level_check = 1
        fg.arrival_tol = 1e-2
        fg.interp_method = 0  # the value of the cell holding the point
        rd.fgmax_data.fgmax_grids.append(fg)

    rd.write(out_dir=case_dir)
    meta = dict(nx=nx, ny=ny, dx=dx, tfinal=tfinal, bc=bc, manning=manning,
                wall_height=wall_height, dry_tolerance=dry_tolerance, margin=margin,
                construction_max_abs_err=float(np.max(np.abs(chk - zb))))
    json.dump(meta, open(os.path.join(case_dir, "case.json"), "w"), indent=1)
    return meta


# ----------------------------------------------------------------------------------------------
# Sub-commands
# ----------------------------------------------------------------------------------------------
def geoclaw_case_quiet(case_dir, z, h, dx, **kw):
    """geoclaw_case with clawpack's own prints (fgmax_tools) kept off stdout, so a script's table
    stays clean."""
    with open(os.devnull, "w") as devnull, contextlib.redirect_stdout(devnull):
        geoclaw_case(case_dir, z, h, dx, **kw)


def cmd_grids(args):
    repo, work = os.path.abspath(args.repo), os.path.abspath(args.work)
    src = os.path.join(repo, "data", "kot_dambreak")
    dem5 = read_raster(os.path.join(src, "dem.tif"))
    water5 = read_raster(os.path.join(src, "water.tif"))
    h5 = water_column(dem5)
    diff = np.nanmax(np.abs(f32(h5).values - water5.values))
    print(f"derived 5 m water vs water.tif: max |diff| = {diff:.3g} m, cells {np.count_nonzero(h5.values > 0)}"
          f" vs {np.count_nonzero(water5.values > 0)}")
    levels = [float(v) for v in args.levels.split(",")]
    zmax = np.nanmax(dem5.values)
    wall = float(math.ceil((zmax + 500.0) / 100.0) * 100.0)
    info = {}
    for res in levels:
        name = "r" + res_name(res)
        gdir = os.path.join(work, "grids", name)
        os.makedirs(gdir, exist_ok=True)
        ratio = res / 5.0
        if abs(ratio - 1.0) < 1e-9:
            dem, water = dem5, water5  # the case's own files
        elif ratio > 1:
            f = int(round(ratio))
            dem = f32(coarsen_mean(dem5, f))
            water = f32(water_column(dem))
        else:
            f = int(round(1.0 / ratio))
            dem = f32(refine_bilinear(dem5, f))
            water = f32(water_column(dem))
        write_raster(os.path.join(gdir, "dem.tif"), dem)
        write_raster(os.path.join(gdir, "water.tif"), Raster(np.where(np.isnan(water.values), 0.0, water.values),
                                                             water.ulx, water.uly, water.dx, water.wkt), nodata=-9999.0)
        with open(os.path.join(gdir, "talus.run"), "w") as fo:
            fo.write(talus_runfile(os.path.join(src, "kot_dambreak.run"), "dem.tif", "water.tif"))
        # reread exactly what Talus reads
        dem_r = read_raster(os.path.join(gdir, "dem.tif"))
        h_r = np.nan_to_num(read_raster(os.path.join(gdir, "water.tif")).values)
        h_r[np.isnan(dem_r.values)] = 0.0
        vol = float(h_r.sum() * dem_r.dx ** 2)
        meta = geoclaw_case(os.path.join(work, "geoclaw", "kot_" + name), dem_r.values, h_r, dem_r.dx,
                            tfinal=90.0, nout=6, bc="extrap", manning=0.05, wall_height=wall,
                            out_format="binary64", fgmax=True)
        if name == "r5":  # sensitivity: GeoClaw's default dry tolerance instead of Talus's 1e-6 m
            geoclaw_case(os.path.join(work, "geoclaw", "kot_" + name + DRY3), dem_r.values, h_r, dem_r.dx,
                         tfinal=90.0, nout=6, bc="extrap", manning=0.05, wall_height=wall,
                         out_format="binary64", fgmax=True, dry_tolerance=1e-3)
        info[name] = dict(res_nominal=res, dx=dem_r.dx, nx=dem_r.nx, ny=dem_r.ny,
                          data_cells=int(np.count_nonzero(~np.isnan(dem_r.values))),
                          wet_cells=int(np.count_nonzero(h_r > 0)), volume_m3=vol, wall_height=wall,
                          construction_err=meta["construction_max_abs_err"])
        print(f"{name}: {dem_r.nx} x {dem_r.ny} cells of {dem_r.dx:.4f} m, water {vol:.1f} m3 "
              f"in {info[name]['wet_cells']} cells; GeoClaw wall {wall} m")
    json.dump(info, open(os.path.join(work, "grids", "grids.json"), "w"), indent=1)


RITTER_LENGTH, RITTER_DAM, RITTER_HL, RITTER_T, RITTER_NY = 2000.0, 1000.0, 1.0, 50.0, 4


def ritter_h(x, t=RITTER_T, x0=RITTER_DAM, hl=RITTER_HL, g=GRAVITY):
    c0 = math.sqrt(g * hl)
    xi = (np.asarray(x, dtype=np.float64) - x0) / t
    h = np.where(xi <= -c0, hl, (2 * c0 - xi) ** 2 / (9 * g))
    return np.where(xi >= 2 * c0, 0.0, h)


def ritter_cell_averages(nx, dx, sub=64):
    """Exact cell averages of Ritter's h (midpoint rule on `sub` sub-cells; the solution is smooth
    but for the two kinks and the front, where this is accurate to ~1e-9 m per cell)."""
    off = (np.arange(sub) + 0.5) / sub * dx
    x = (np.arange(nx) * dx)[:, None] + off[None, :]
    return ritter_h(x).mean(axis=1)


def talus_run_text(manning, t_end_s, precision, boundary, comment=None):
    """A Talus run-file for the peer cases: DEM and initial water from dem.tif / water.tif beside it,
    slope correction off (GeoClaw's equations), van Leer + HLLC at CFL 0.5, outputs in output/."""
    lines = ["[Talus run file]"]
    if comment:
        lines.append("# " + comment)
    lines += ["[Input]", "Map Directory=.", "DEM=dem.tif", "Include Initial Water=1", "Initial Fluid Height=water.tif",
              "[Flow]", "Manning=%r" % (manning,), "Slope Correction=0",
              "[Time]", "Start Time=0", "End Time=%r" % (t_end_s / 60.0,), "Timestep=%r" % (t_end_s,),
              "[Numerics]", "CFL=0.5", "Limiter=vanleer", "Riemann Solver=hllc", "Precision=" + precision,
              "Boundary Type=" + boundary, "[Output]", "Output Directory=output"]
    return "\n".join(lines) + "\n"



def cmd_ritter(args):
    work = os.path.abspath(args.work)
    info = {}
    for dx in [float(v) for v in args.dx.split(",")]:
        name = "dx" + res_name(dx)
        rdir = os.path.join(work, "ritter", name)
        os.makedirs(rdir, exist_ok=True)
        nx = int(round(RITTER_LENGTH / dx))
        ny = RITTER_NY
        xc = (np.arange(nx) + 0.5) * dx
        h = np.tile(np.where(xc < RITTER_DAM, RITTER_HL, 0.0), (ny, 1))
        z = np.zeros((ny, nx))
        write_raster(os.path.join(rdir, "dem.tif"), Raster(z, 0.0, ny * dx, dx))
        write_raster(os.path.join(rdir, "water.tif"), Raster(h, 0.0, ny * dx, dx))
        with open(os.path.join(rdir, "talus.run"), "w") as fo:
            fo.write(talus_run_text(0, RITTER_T, "float", "wall",
                                    "Ritter dam break (bench/peers): flat frictionless channel, walls on every side"))
        for suffix, tol in (("", 1e-6), (DRY3, 1e-3)):
            geoclaw_case(os.path.join(work, "geoclaw", "ritter_" + name + suffix), z, h, dx, tfinal=RITTER_T,
                         nout=1, bc="wall", manning=0.0, wall_height=10.0, out_format="ascii", fgmax=False,
                         dry_tolerance=tol)
        info[name] = dict(dx=dx, nx=nx, ny=ny)
        print(f"ritter {name}: {nx} x {ny} cells")
    json.dump(info, open(os.path.join(work, "ritter", "ritter.json"), "w"), indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("grids")
    g.add_argument("repo")
    g.add_argument("work")
    g.add_argument("--levels", default="10,5,2.5")
    g.set_defaults(fn=cmd_grids)
    r = sub.add_parser("ritter")
    r.add_argument("work")
    r.add_argument("--dx", default="1,0.5,0.25")
    r.set_defaults(fn=cmd_ritter)
    args = ap.parse_args()
    args.fn(args)


if __name__ == "__main__":
    main()
