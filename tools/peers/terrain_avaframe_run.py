#!/usr/bin/env python3
"""Run AvaFrame com1DFA (installed package, `pip install avaframe`) with Coulomb friction on one
terrain case of /work/shared/data/terrain (issue 13, part 5).

Builds an avalanche directory  WORK/avaframe/<case>/Inputs/{dem.tif, REL/rel<case>.tif, CFGs-free}
from the case's dem.tif and release.tif (release thickness, slope-normal, raster on the DEM grid),
writes a com1DFA override ini, runs com1DFAMain and records the wall time in run_info.json.

Run with the AvaFrame virtual environment's python:
    /work/avaframe-venv/bin/python tools/peers/terrain_avaframe_run.py CASE_DIR WORK_DIR [--mu 0.4663]
No AvaFrame code is copied here; only its public entry points are called.
"""
import argparse
import json
import pathlib
import shutil
import sys
import time

import rasterio


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case_dir", type=pathlib.Path)
    ap.add_argument("work_dir", type=pathlib.Path)
    ap.add_argument("--mu", type=float, default=0.4663, help="Coulomb friction coefficient tan(delta)")
    ap.add_argument("--tend", type=float, default=150.0, help="end time [s] (stop criterion may end earlier)")
    ap.add_argument("--ncpu", default="2")
    args = ap.parse_args()

    case = args.case_dir.resolve().name
    ava = (args.work_dir / "avaframe" / case).resolve()
    if ava.exists():
        shutil.rmtree(ava)
    (ava / "Inputs" / "REL").mkdir(parents=True)
    shutil.copy(args.case_dir / "dem.tif", ava / "Inputs" / "dem.tif")
    relName = "rel" + case[3:] if case.startswith("ava") else "rel" + case
    shutil.copy(args.case_dir / "release.tif", ava / "Inputs" / "REL" / (relName + ".tif"))

    with rasterio.open(args.case_dir / "dem.tif") as ds:
        cell = abs(ds.transform.a)

    # com1DFA override: Coulomb friction, no entrainment/resistance ("null" simulation), no dam,
    # no secondary release, the DEM's own cell size as mesh (no remeshing, so outputs stay on the
    # input grid and the release raster matches the DEM), final flow thickness FT exported.
    override = ava / "com1DFA_override.ini"
    override.write_text(
        "[GENERAL]\n"
        "simTypeList = null\n"
        "frictModel = Coulomb\n"
        f"mucoulomb = {args.mu}\n"
        f"tEnd = {args.tend}\n"
        "dam = False\n"
        "secRelArea = False\n"
        f"meshCellSize = {cell!r}\n"
        "resType = ppr|pft|pfv|FT|timeInfo\n"
        "[INPUT]\n"
        f"releaseScenario = {relName}\n"
    )

    from avaframe.com1DFA import com1DFA
    from avaframe.in3Utils import cfgUtils, logUtils

    cfgMain = cfgUtils.getGeneralConfig()
    cfgMain["MAIN"]["avalancheDir"] = str(ava)
    cfgMain["MAIN"]["nCPU"] = str(args.ncpu)
    cfgMain["FLAGS"]["savePlot"] = "False"
    cfgMain["FLAGS"]["createReport"] = "False"
    cfgMain["FLAGS"]["ReportDir"] = "False"
    cfgMain["FLAGS"]["showPlot"] = "False"
    logUtils.initiateLogger(str(ava), "runCom1DFA_coulomb")
    cfg = cfgUtils.getModuleConfig(com1DFA, str(ava), fileOverride=override, toPrint=False)

    t0 = time.time()
    dem, plotDict, reportDictList, simDF = com1DFA.com1DFAMain(cfgMain, cfgInfo=cfg)
    wall = time.time() - t0

    info = {"case": case, "avalancheDir": str(ava), "wall_s": wall, "mu": args.mu, "tEnd": args.tend,
            "meshCellSize": cell}
    try:
        import avaframe
        info["avaframe_version"] = getattr(avaframe, "__version__", None)
    except Exception:
        pass
    try:
        from importlib.metadata import version
        info["avaframe_version"] = version("avaframe")
    except Exception:
        pass
    try:
        rep = reportDictList[0] if reportDictList else {}
        info["simName"] = rep.get("simName", {}).get("name") if isinstance(rep.get("simName"), dict) else None
        info["final_time_s"] = rep.get("Simulation Parameters", {}).get("Stop time [s]")
        info["comp_time_s"] = rep.get("Simulation Parameters", {}).get("Computation time [s]")
    except Exception as e:  # report structure is not part of the public API
        info["report_error"] = repr(e)
    (ava / "run_info.json").write_text(json.dumps(info, indent=2, default=str))
    print(json.dumps(info, indent=2, default=str))


if __name__ == "__main__":
    sys.exit(main())
