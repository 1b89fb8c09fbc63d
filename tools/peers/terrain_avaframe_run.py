#!/usr/bin/env python3
"""Run AvaFrame com1DFA (installed package, `pip install avaframe`) with Coulomb friction (issue 13,
part 5) or Voellmy friction (issue 19, item 4) on one terrain case of /work/shared/data/terrain.

Builds an avalanche directory  WORK/avaframe/<case>/Inputs/{dem.tif, REL/rel<case>.tif, CFGs-free}
from the case's dem.tif and release.tif (release thickness, slope-normal, raster on the DEM grid),
writes a com1DFA override ini, runs com1DFAMain and records the wall time in run_info.json.

Run with the AvaFrame virtual environment's python:
    /work/avaframe-venv/bin/python tools/peers/terrain_avaframe_run.py CASE_DIR WORK_DIR [--mu 0.4663]
    ... --friction voellmy [--mu-voellmy M --xi-voellmy X] [--tend 400]
With --friction voellmy, mu and xi default to muvoellmy / xsivoellmy of the installed package's own
com1DFA/com1DFACfg.ini (read at run time, so they are exactly AvaFrame's standard values).
No AvaFrame code is copied here; only its public entry points are called.
"""
import argparse
import json
import pathlib
import shutil
import sys
import time

import rasterio


def avaframe_defaults():
    """The [GENERAL] section of the installed package's com1DFA/com1DFACfg.ini (AvaFrame's defaults)."""
    import configparser
    from avaframe.com1DFA import com1DFA
    cp = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",))
    cp.optionxform = str
    cp.read(pathlib.Path(com1DFA.__file__).with_name("com1DFACfg.ini"))
    return {k.lower(): v for k, v in cp["GENERAL"].items()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case_dir", type=pathlib.Path)
    ap.add_argument("work_dir", type=pathlib.Path)
    ap.add_argument("--mu", type=float, default=0.4663, help="Coulomb friction coefficient tan(delta)")
    ap.add_argument("--friction", choices=["coulomb", "voellmy"], default="coulomb")
    ap.add_argument("--mu-voellmy", type=float, help="Voellmy mu (default: muvoellmy of com1DFACfg.ini)")
    ap.add_argument("--xi-voellmy", type=float, help="Voellmy xi [m/s2] (default: xsivoellmy of com1DFACfg.ini)")
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
    # Voellmy: frictModel = Voellmy with AvaFrame's own standard parameters unless given.
    if args.friction == "voellmy":
        d = avaframe_defaults()
        args.mu_voellmy = float(d["muvoellmy"]) if args.mu_voellmy is None else args.mu_voellmy
        args.xi_voellmy = float(d["xsivoellmy"]) if args.xi_voellmy is None else args.xi_voellmy
        fric = f"frictModel = Voellmy\nmuvoellmy = {args.mu_voellmy!r}\nxsivoellmy = {args.xi_voellmy!r}\n"
    else:
        fric = f"frictModel = Coulomb\nmucoulomb = {args.mu}\n"
    override = ava / "com1DFA_override.ini"
    override.write_text(
        "[GENERAL]\n"
        "simTypeList = null\n"
        + fric +
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
    logUtils.initiateLogger(str(ava), "runCom1DFA_" + args.friction)
    cfg = cfgUtils.getModuleConfig(com1DFA, str(ava), fileOverride=override, toPrint=False)

    t0 = time.time()
    dem, plotDict, reportDictList, simDF = com1DFA.com1DFAMain(cfgMain, cfgInfo=cfg)
    wall = time.time() - t0

    info = {"case": case, "avalancheDir": str(ava), "wall_s": wall, "friction": args.friction,
            "tEnd": args.tend, "meshCellSize": cell}
    if args.friction == "voellmy":
        info.update(muvoellmy=args.mu_voellmy, xsivoellmy=args.xi_voellmy)
    else:
        info["mu"] = args.mu
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
