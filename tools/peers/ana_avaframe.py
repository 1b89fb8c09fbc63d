#!/usr/bin/env python3
"""AvaFrame's analytic tests run by both codes: com1DFA (installed package) and Talus (issue 19, item 4).

  ana_avaframe.py run  TEST WORK_DIR --talus BIN [--skip-avaframe] [--skip-talus]
  ana_avaframe.py table WORK_DIR [--md FILE]

TEST is
  simisol   the similarity solution of Hutter, Siegel, Savage & Nohguchi (1993) for a paraboloid
            granular mass gliding down a 35 deg plane with Coulomb friction 25 deg, K = 1
            (AvaFrame's data/avaSimilaritySol test, ana1Tests/simiSolTest.py);
  dambreak  the dam break of a 1 m granular layer on a 22 deg plane with Coulomb friction 21 deg
            (Faccanoni & Mangeney 2012, test 2 case 1.2, i.e. Mangeney et al. 2000's solution;
            AvaFrame's data/avaDamBreak test, ana1Tests/damBreak.py).

The scene parameters are those of AvaFrame's own test configurations
(avaframe/data/avaSimilaritySol/Inputs/simiSol_com1DFACfg.ini and
avaframe/data/avaDamBreak/Inputs/damBreak_com1DFACfg.ini in github.com/OpenNHM/AvaFrame, EUPL v1.2),
written out here as values; the inclined planes are generated here on a 3 m grid (the finer of the two
meshes AvaFrame's run scripts use, sphKernelRadius = meshCellSize = 3 m), so com1DFA does not remesh
and both codes start from the same DEM and release raster. The particle numbers are one of the test's
variations (nPPK0 = 15, aPPK = -1.5: com1DFA's defaults) instead of its 12-run sweep. One deviation:
the dam-break test's iniStep = True (particle redistribution before the start) is refused by AvaFrame
2.1 ("currently not supported due to recent refactoring of thickness handling"), so iniStep = False.

The analytic solutions come from the installed package (simiSolTest.mainSimilaritySol and
getSimiSolParameters, damBreak.damBreakSol); the errors are computed here, the same way for both codes,
on each code's own output grid at t = tSave = 5 s:
  L1 rel. h   = sum |h_num - h_ana| / sum h_ana           (h slope-normal; Talus: vertical h * cos)
  L1 rel. hu  = sum |h_num |u|_num - h_ana |u|_ana| / sum h_ana |u|_ana, with |u| the horizontal
                speed sqrt(ux^2 + uy^2) (Talus writes only the speed magnitude, horizontally; com1DFA's
                Vx, Vy are the horizontal components), for the dam break the x (downslope) component.
  L2 rel. h   = sqrt(sum (h_num - h_ana)^2 / sum h_ana^2) (AvaFrame reports this one)
Domain: simisol the whole grid; dambreak AvaFrame's comparison window (getDamExtend: from the middle
of the material xMidAna to xEnd, yStart..yEnd), because the analytic solution ignores the rear end.
"""
import argparse
import json
import math
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np
import rasterio
from rasterio.transform import from_origin

CELL = 3.0
TESTS = {
    "simisol": dict(slope=35.0, delta=25.0, x0=-200.01, y0=-250.01, nx=667, ny=167, z0=1500.0, tsave=5.0),
    "dambreak": dict(slope=22.0, delta=21.0, x0=-602.5, y0=-402.5, nx=402, ny=269, z0=2200.0, tsave=5.0),
}

SIMI_INI = """[GENERAL]
simTypeList = null
resType = FT|FV|Vx|Vy|Vz
tSteps = 0:1
initPartDistType = random
tEnd = 5
sphKernelRadiusTimeStepping = True
cMax = 0.02
sphOption = 2
sphKernelRadius = 3
viscOption = 1
massPerParticleDeterminationMethod = MPPKR
sphKR0 = 5
nPPK0 = 15
aPPK = -1.5
thresholdMassSplit = 5
meshCellSize = 3
subgridMixingFactor = 10
frictModel = Coulomb
explicitFriction = 1
mucoulomb = 0.466307658
dam = False
secRelArea = False
[INPUT]
releaseScenario = rel1
[SIMISOL]
L_x = 80.
L_y = 80.
relTh = 4.
bedFrictionAngle = 25.
internalFrictionAngle = 25.
planeinclinationAngle = 35.
flagEarth = False
dtSol = 50.
tSave = 5
paramInfo = sphKernelRadius|aPPK|nPPK0|nPart
onlyLast = False
plotErrorTime = False
plotSequence = False
relativError = True
scaleCoef = 1.02
"""

DAM_INI = """[GENERAL]
simTypeList = null
resType = FT|FV|Vx|Vy|Vz
tSteps = 0:1
iniStep = False
maxIterations = 30
bufferZoneFactor = 4
fdOptionIni = False
tEnd = 5
sphKernelRadiusTimeStepping = True
cMax = 0.01
sphOption = 2
viscOption = 0
massPerParticleDeterminationMethod = MPPKR
sphKR0 = 5
nPPK0 = 15
aPPK = -1.5
thresholdMassSplit = 10
meshCellSize = 3
sphKernelRadius = 3
explicitFriction = 1
frictModel = Coulomb
mucoulomb = 0.3838640350354158
dam = False
secRelArea = False
relThFromFile = False
relTh = 1
[INPUT]
releaseScenario = rel1
[DAMBREAK]
phi = 22
delta = 21
u0 = 0.
tEnd = 30
dt = 0.1
dx = 0.5
xStart = -200
xEnd = 220
yStart = -50
yEnd = 50
xBack = -120
tSave = 5
projectVelocity = False
paramInfo = sphKernelRadius|aPPK|nPPK0|nPart
onlyLast = False
plotErrorTime = False
plotSequence = False
relativError = True
scaleCoef = 1.05
"""


def grid(p):
    x = p["x0"] + CELL * np.arange(p["nx"])
    y = p["y0"] + CELL * np.arange(p["ny"])
    X, Y = np.meshgrid(x, y[::-1])  # rows from the top (north), as the GeoTIFFs
    return X, Y


def write_tif(path, a, p):
    tr = from_origin(p["x0"] - CELL / 2, p["y0"] + CELL * (p["ny"] - 0.5), CELL, CELL)
    with rasterio.open(path, "w", driver="GTiff", width=p["nx"], height=p["ny"], count=1, dtype="float64",
                       transform=tr, nodata=-9999.0) as ds:
        ds.write(a.astype(np.float64), 1)


def scene(test, p):
    """DEM (plane falling in +x) and slope-normal release thickness on the grid."""
    X, Y = grid(p)
    th = math.radians(p["slope"])
    dem = p["z0"] - (X - p["x0"]) * math.tan(th)
    if test == "simisol":  # paraboloid, 4 m at the centre, radius 80 m along the slope (x / cos)
        rel = 4.0 * (1 - (X / math.cos(th)) ** 2 / 80.0 ** 2 - Y ** 2 / 80.0 ** 2)
        rel = np.where(rel < 0, 0.0, rel)
    else:  # AvaFrame's rel1.shp: the rectangle x in [-120, 0], y in [-80, 80], relTh = 1 m
        rel = np.where((X >= -120) & (X <= 0) & (Y >= -80) & (Y <= 80), 1.0, 0.0)
    return dem, rel


def run_avaframe(test, p, work):
    ava = (work / test / "avaframe").resolve()
    if ava.exists():
        shutil.rmtree(ava)
    (ava / "Inputs" / "REL").mkdir(parents=True)
    dem, rel = scene(test, p)
    write_tif(ava / "Inputs" / "dem.tif", dem, p)
    if test == "simisol":  # the paraboloid as a thickness raster
        write_tif(ava / "Inputs" / "REL" / "rel1.tif", rel, p)
    else:  # the dam as AvaFrame's polygon rel1.shp, relTh = 1 (as its test)
        import shapefile
        with shapefile.Writer(str(ava / "Inputs" / "REL" / "rel1"), shapeType=shapefile.POLYGON) as w:
            w.field("id", "N", 10)
            w.poly([[(-120.0, -80.0), (-120.0, 80.0), (0.0, 80.0), (0.0, -80.0), (-120.0, -80.0)]])
            w.record(1)
    ini = ava / "Inputs" / (test + "_com1DFACfg.ini")
    ini.write_text(SIMI_INI if test == "simisol" else DAM_INI)
    from avaframe.com1DFA import com1DFA
    from avaframe.in3Utils import cfgUtils, logUtils
    cfgMain = cfgUtils.getGeneralConfig()
    cfgMain["MAIN"]["avalancheDir"] = str(ava)
    cfgMain["MAIN"]["nCPU"] = "2"
    for k in ("savePlot", "createReport", "ReportDir", "showPlot"):
        cfgMain["FLAGS"][k] = "False"
    logUtils.initiateLogger(str(ava), "run_" + test)
    cfg = cfgUtils.getModuleConfig(com1DFA, str(ava), fileOverride=ini, toPrint=False)
    t0 = time.time()
    _, _, _, simDF = com1DFA.com1DFAMain(cfgMain, cfgInfo=cfg)
    wall = time.time() - t0
    info = {"wall_s": wall, "simNames": list(simDF["simName"]), "nPart": [int(v) for v in simDF.get("nPart", [])]
            if "nPart" in simDF else None}
    (ava / "run_info.json").write_text(json.dumps(info, indent=2, default=str))


def run_talus(test, p, work, talus):
    tdir = (work / test / "talus").resolve()
    tdir.mkdir(parents=True, exist_ok=True)
    dem, rel = scene(test, p)
    th = math.radians(p["slope"])
    write_tif(tdir / "dem.tif", dem, p)
    write_tif(tdir / "solids_vertical.tif", rel / math.cos(th), p)  # h_v = h_n / cos(theta)
    delta = math.radians(p["delta"])
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from terrain_compare import solids_runfile
    run = solids_runfile(f"# AvaFrame analytic test '{test}' (tools/peers/ana_avaframe.py): plane {p['slope']} deg, "
                         f"Coulomb {p['delta']} deg, K = 1.", "dem.tif", delta, p["tsave"], 1,
                         "Initial Solid Density=200\n")
    (tdir / "case.run").write_text(run)
    subprocess.run([talus, "run", "case.run", "--out", "out", "--precision", "double", "--overwrite", "--quiet"],
                   cwd=tdir, check=True)


def read(path):
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from terrain_compare import read as read_raster
    return np.nan_to_num(read_raster(path)[0], nan=0.0)


def analytic(test, p, work, header, t):
    """Analytic h (slope-normal) and horizontal speed at time t on the grid of `header` (rows from
    the bottom, AvaFrame's convention), from the installed package (each code is compared at the
    time of its own output: com1DFA's field nearest tSave is at 5.04 s, Talus ends at 5.00 s)."""
    ini = work / test / "analytic.ini"
    ini.write_text(SIMI_INI if test == "simisol" else DAM_INI)
    from avaframe.com1DFA import com1DFA
    from avaframe.in3Utils import cfgUtils
    cfg = cfgUtils.getModuleConfig(com1DFA, fileOverride=ini, toPrint=False)
    if test == "simisol":
        from avaframe.ana1Tests import simiSolTest
        sol = simiSolTest.mainSimilaritySol(ini)
        it = np.searchsorted(sol["time"], t)
        d = simiSolTest.getSimiSolParameters(sol, header, it, cfg["SIMISOL"], cfg["SIMISOL"].getfloat("relTh"),
                                             cfg["GENERAL"].getfloat("gravAcc"))
        return d["hSimi"], np.hypot(d["vxSimi"], d["vySimi"]), None
    from avaframe.ana1Tests import damBreak
    cfgMain = cfgUtils.getGeneralConfig()
    cfgMain["FLAGS"]["showPlot"] = "False"
    out = work / test / "analytic_plots"
    out.mkdir(exist_ok=True)
    sol = damBreak.damBreakSol(str(work / test), cfgMain, cfg, out)
    it = int(np.argmin(np.abs(sol["tAna"] - t)))
    xs = header["xllcenter"] + header["cellsize"] * np.arange(header["ncols"])
    h1 = np.interp(xs, sol["xAna"], sol["hAna"][:, it])
    u1 = np.interp(xs, sol["xAna"], sol["uAna"][:, it]) * math.cos(math.radians(p["slope"]))  # along slope -> horizontal
    h = np.tile(h1, (header["nrows"], 1))
    u = np.tile(u1, (header["nrows"], 1))
    _, c0, c1, r0, r1 = damBreak.getDamExtend(header, sol["xMidAna"][it], cfg["DAMBREAK"])
    mask = np.zeros_like(h, dtype=bool)
    mask[r0:r1, c0:c1] = True
    return h, u, mask


def errors(h, hu, ha, hua, mask):
    if mask is None:
        mask = np.ones_like(h, dtype=bool)
    h, hu, ha, hua = (a[mask] for a in (h, hu, ha, hua))
    return {"L1_h": float(np.abs(h - ha).sum() / ha.sum()),
            "L1_hu": float(np.abs(hu - hua).sum() / hua.sum()),
            "L2_h": float(math.sqrt(((h - ha) ** 2).sum() / (ha ** 2).sum())),
            "mass_ratio_window": float(h.sum() / ha.sum())}


def evaluate(test, p, work):
    res = {}
    header = {"ncols": p["nx"], "nrows": p["ny"], "xllcenter": p["x0"], "yllcenter": p["y0"], "cellsize": CELL}
    th = math.radians(p["slope"])
    ava = work / test / "avaframe"
    if (ava / "run_info.json").exists():
        from avaframe.com1DFA import com1DFA
        info = json.loads((ava / "run_info.json").read_text())
        fields, fh, times = com1DFA.readFields(ava, ["FT", "FV", "Vx", "Vy", "Vz"], simName=info["simNames"][0],
                                               flagAvaDir=True, comModule="com1DFA")
        i = int(np.argmin(np.abs(np.asarray(times) - p["tsave"])))
        f = fields[i]
        assert f["FT"].shape == (p["ny"], p["nx"]) and abs(fh["xllcenter"] - p["x0"]) < 1e-6, "com1DFA remeshed"
        ha, ua, mask = analytic(test, p, work, header, float(times[i]))
        h = f["FT"]
        u = np.abs(f["Vx"]) if test == "dambreak" else np.hypot(f["Vx"], f["Vy"])
        e = errors(h, h * u, ha, ha * ua, mask)
        e.update(time_s=float(times[i]), wall_s=info["wall_s"], nPart=info.get("nPart"))
        res["AvaFrame com1DFA"] = e
    out = work / test / "talus" / "out"
    if (out / "summary.json").exists():
        s = json.loads((out / "summary.json").read_text())
        ha, ua, mask = analytic(test, p, work, header, float(s["simulated_s"]))
        h = read(out / "hsfinal.tif")[::-1] * math.cos(th)  # rows from the bottom, as AvaFrame's fields
        u = read(out / "vsfinal.tif")[::-1]
        e = errors(h, h * u, ha, ha * ua, mask)
        e.update(time_s=s["simulated_s"], wall_s=s.get("wall_time_s", s.get("wall_s")))
        res["Talus"] = e
    return res


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("test", choices=sorted(TESTS))
    r.add_argument("work_dir", type=pathlib.Path)
    r.add_argument("--talus")
    r.add_argument("--skip-avaframe", action="store_true")
    r.add_argument("--skip-talus", action="store_true")
    r.add_argument("--evaluate-only", action="store_true", help="only recompute the errors of existing runs")
    t = sub.add_parser("table")
    t.add_argument("work_dir", type=pathlib.Path)
    t.add_argument("--md")
    a = ap.parse_args()
    work = a.work_dir.resolve()
    if a.cmd == "run":
        p = TESTS[a.test]
        (work / a.test).mkdir(parents=True, exist_ok=True)
        if not (a.skip_avaframe or a.evaluate_only):
            run_avaframe(a.test, p, work)
        if not (a.skip_talus or a.evaluate_only):
            run_talus(a.test, p, work, a.talus)
        res = evaluate(a.test, p, work)
        (work / a.test / "errors.json").write_text(json.dumps(res, indent=2))
        print(json.dumps(res, indent=2))
        return
    lines = ["| test | code | time [s] | L1 rel. h | L1 rel. h u (horizontal speed) | L2 rel. h | mass in window / analytic | wall [s] |",
             "|---|---|---|---|---|---|---|---|"]
    for test in sorted(TESTS):
        f = work / test / "errors.json"
        if not f.exists():
            continue
        for code, e in json.loads(f.read_text()).items():
            lines.append(f"| {test} | {code} | {e['time_s']:.2f} | {e['L1_h']:.4f} | {e['L1_hu']:.4f} | {e['L2_h']:.4f} | "
                         f"{e['mass_ratio_window']:.3f} | {e['wall_s']:.1f} |")
    txt = "\n".join(lines) + "\n"
    print(txt)
    if a.md:
        pathlib.Path(a.md).write_text(txt)


if __name__ == "__main__":
    sys.exit(main())
