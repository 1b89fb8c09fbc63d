#!/usr/bin/env python3
"""How much the paper's fracture regimes owe to the particles' numerical terms (issue 18, item 1).

  particle_regime_study.py WORK_DIR [--talus build/src/talus] [--only NAME,...] [--jobs 1]

Runs variants of the paper's numerical tests (data/paper_setup1_B, paper_setup2_B; A and C as
controls) with `talus run` and tabulates, per run, the share of the particle mass whose bonds are
broken (c/c0 < 0.1) at the end, the mean c/c0, the deposit's downslope extent, the peak kinetic
energy and the energy the artificial viscosity dissipated (summary.json). The variants change one
numerical choice at a time, never the material:
  - the artificial viscosity (alpha_Pi, beta_Pi): the paper's (1, 1), Bui et al.'s (0.1, 0), none (0, 0),
    each with the scenes' artificial stress (eps_0 = 0.3); and Talus's defaults ("default": Bui's
    viscosity without artificial stress);
  - the cohesion c of scenario B across its regime boundary (60-120 kPa);
  - particles per cell (4, the scenes' value; 9) and the smoothing length (h = 1 and 1.5 cells).
The particle layers are read with sqlite3; with GDAL's Python bindings (osgeo) the deposit's extent
is given from the DEM's west edge (the scenes' x), else in world coordinates. Results go to
WORK_DIR/regime_study.csv (the runs of this invocation) and a Markdown table on standard output. Each run takes 9-120 s on two
PoCL cores.
"""
import argparse
import csv
import json
import os
import pathlib
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from particle_layers import read_particle_layer  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BROKEN = 0.1  # c/c0 below which a particle counts as broken (docs/scenes.md)
SLOPE_FOOT_X = 600.0  # where the 30-degree slope of both setups ends [m from the DEM's west edge] (tools/make_paper_scenes.py)


def variants():
    """(name, scene, {run-file key: value}) of every run of the study."""
    out = []
    # The scenes' artificial stress (eps_0 = 0.3) with each viscosity, and Talus's defaults (Bui's
    # viscosity, no artificial stress: "default").
    av = {"paper": ("1", "1"), "bui": ("0.1", "0"), "none": ("0", "0")}
    default = {"Artificial Viscosity Alpha": "0.1", "Artificial Viscosity Beta": "0", "Artificial Stress Epsilon": "0"}
    for setup in ("1", "2"):
        for c in ("60", "75", "85", "90", "120"):
            for tag, (a, b) in av.items():
                out.append((f"s{setup}B_c{c}_av{tag}", f"paper_setup{setup}_B",
                            {"Initial Cohesion": c, "Artificial Viscosity Alpha": a, "Artificial Viscosity Beta": b}))
            out.append((f"s{setup}B_c{c}_default", f"paper_setup{setup}_B", dict(default, **{"Initial Cohesion": c})))
        for scen in ("A", "C"):
            for tag in ("paper", "bui"):
                a, b = av[tag]
                out.append((f"s{setup}{scen}_av{tag}", f"paper_setup{setup}_{scen}",
                            {"Artificial Viscosity Alpha": a, "Artificial Viscosity Beta": b}))
            out.append((f"s{setup}{scen}_default", f"paper_setup{setup}_{scen}", dict(default)))
    for c in ("75", "90"):
        for tag in ("paper", "bui"):
            a, b = av[tag]
            base = {"Initial Cohesion": c, "Artificial Viscosity Alpha": a, "Artificial Viscosity Beta": b}
            out.append((f"s1B_c{c}_av{tag}_ppc9", "paper_setup1_B", dict(base, **{"Particles Per Cell": "9"})))
            out.append((f"s1B_c{c}_av{tag}_h1.5", "paper_setup1_B", dict(base, **{"Smoothing Length Factor": "1.5"})))
    return out


def set_keys(text, keys):
    """The run-file text with each key set (replaced where present, else added to its section)."""
    sections = {"Initial Cohesion": "Solids"}
    for key, value in keys.items():
        pat = re.compile(r"^" + re.escape(key) + r"=.*$", re.M)
        if pat.search(text):
            text = pat.sub(f"{key}={value}", text)
        else:
            sec = sections.get(key, "Particles")
            text = text.replace(f"[{sec}]\n", f"[{sec}]\n{key}={value}\n", 1)
    return text


def read_points(gpkg):
    """(x, mass, cohesion_fraction) of every particle of a Talus particle layer."""
    return [(x, mass, frac) for x, _y, mass, frac in read_particle_layer(gpkg, ("mass", "cohesion_fraction"))]


def x_origin(dem):
    """The DEM's west edge in world coordinates (0 without GDAL's Python bindings)."""
    try:
        from osgeo import gdal
    except ImportError:
        return 0.0
    ds = gdal.Open(str(dem))
    return ds.GetGeoTransform()[0] if ds else 0.0


def run_one(talus, work, name, scene, keys):
    d = work / name
    d.mkdir(parents=True, exist_ok=True)
    src = ROOT / "data" / scene
    for f in src.iterdir():
        if f.suffix == ".tif":
            dst = d / f.name
            if not dst.exists():
                os.symlink(f, dst)
    text = set_keys((src / f"{scene}.run").read_text(), keys)
    (d / "run.run").write_text(text)
    summary = d / "output" / "summary.json"
    if not summary.exists():
        t0 = time.time()
        r = subprocess.run([str(talus), "run", str(d / "run.run")], capture_output=True, text=True)
        if r.returncode != 0:
            sys.stderr.write(f"{name}: talus run failed ({r.returncode}): {r.stderr[-400:]}\n")
            return None
        (d / "wall_s").write_text(f"{time.time() - t0:.1f}\n")
    s = json.loads(summary.read_text())
    pts = read_points(d / "output" / "particles_final.gpkg")
    mass = sum(p[1] for p in pts)
    broken = sum(p[1] for p in pts if p[2] < BROKEN) / mass if mass > 0 else float("nan")
    mean_frac = sum(p[1] * p[2] for p in pts) / mass if mass > 0 else float("nan")
    x0 = x_origin(src / "dem.tif")
    xs = sorted(p[0] - x0 for p in pts)
    # Broken share while the whole block is still on the slope: the last report layer in which no
    # particle has passed the slope foot (regime B must be intact there).
    on_slope, t_slope = float("nan"), float("nan")
    # Report index -> time, as the run wrote it (series/index.csv, as tools/validation/report.py reads it).
    times = {}
    index_csv = d / "output" / "series" / "index.csv"
    if index_csv.exists():
        with open(index_csv) as fh:
            times = {int(r["index"]): float(r["time_s"]) for r in csv.DictReader(fh)}
    for layer in sorted((d / "output" / "particles").glob("particles_*.gpkg")):
        lp = read_points(layer)
        lm = sum(p[1] for p in lp)
        if not lp or max(p[0] - x0 for p in lp) >= SLOPE_FOOT_X or lm <= 0:
            break
        on_slope = sum(p[1] for p in lp if p[2] < BROKEN) / lm
        t_slope = times.get(int(layer.stem.split("_")[1]), float("nan"))
    peak_ke = 0.0
    with open(d / "output" / "diagnostics.csv") as fh:
        for row in csv.DictReader(fh):
            peak_ke = max(peak_ke, float(row["particle_kinetic_J"]))
    part = s.get("particles", {})
    wall = float((d / "wall_s").read_text()) if (d / "wall_s").exists() else float("nan")
    return dict(name=name, scene=scene, **{k.lower().replace(" ", "_"): v for k, v in keys.items()},
                broken=broken, broken_on_slope=on_slope, slope_layer=t_slope, mean_c_frac=mean_frac, x_min=xs[0] if xs else float("nan"),
                x_max=xs[-1] if xs else float("nan"), particles=len(pts), peak_ke_J=peak_ke,
                viscous_J=part.get("viscous_dissipation_J", float("nan")),
                art_stress_J=part.get("art_stress_work_J", float("nan")), wall_s=wall)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work", type=pathlib.Path)
    ap.add_argument("--talus", type=pathlib.Path, default=ROOT / "build" / "src" / "talus")
    ap.add_argument("--only", default="", help="comma-separated run names (default: all)")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    only = set(filter(None, a.only.split(",")))
    results = []
    for name, scene, keys in variants():
        if only and name not in only:
            continue
        r = run_one(a.talus, a.work, name, scene, keys)
        if r:
            results.append(r)
            print(f"{name}: broken {100 * r['broken']:.0f} % (on the slope {100 * r['broken_on_slope']:.0f} % at "
                  f"{r['slope_layer']:.0f} s), "
                  f"mean c/c0 {r['mean_c_frac']:.2f}, "
                  f"x {r['x_min']:.0f}-{r['x_max']:.0f} m, viscous {r['viscous_J']:.3g} J of peak KE "
                  f"{r['peak_ke_J']:.3g} J, {r['wall_s']:.0f} s", flush=True)
    if not results:
        return 1
    keys = sorted({k for r in results for k in r}, key=lambda k: list(results[0]).index(k) if k in results[0] else 99)
    with open(a.work / "regime_study.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(results)
    print("\n| run | broken on the slope | broken at the end (mass) | mean c/c0 | deposit x (m) | viscous dissipation / peak KE (%) |")
    print("|---|---|---|---|---|---|")
    for r in results:
        ratio = r["viscous_J"] / r["peak_ke_J"] if r["peak_ke_J"] > 0 else float("nan")
        print(f"| {r['name']} | {100 * r['broken_on_slope']:.0f} % | {100 * r['broken']:.0f} % | {r['mean_c_frac']:.2f} | "
              f"{r['x_min']:.0f}–{r['x_max']:.0f} | {100 * ratio:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
