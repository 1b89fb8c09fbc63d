#!/usr/bin/env python3
"""Accuracy against run time: figures and tables from the CSV(s) of bench/bench_pareto.cpp.

For every grid case (ritter, stoker, thacker, mangeney) it draws the L1 error against the wall time
of every run (log-log; colour: limiter, marker: precision, size: CFL) with the Pareto front (the
runs no other run beats in both error and time) joined by a line, into IMAGE_DIR/pareto_CASE.png.
For the particle runs it draws the stiffness trade-off (change of the front and of the thickness
field against the stiffest run, and the wall time, against Young's modulus E) into
IMAGE_DIR/pareto_particles.png. With --markdown it also prints the Pareto-optimal runs of each case
and the stiffness table as markdown (the tables of docs/validation_parts/pareto.md).

usage: plot_pareto.py [--markdown] IMAGE_DIR CSV [CSV ...]
  (the CSVs of several bench_pareto invocations may be given; their rows are concatenated)

Needs matplotlib (Debian: python3-matplotlib); the PNGs are drawn at 80 dpi (well below 150 kB).
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 80
LIMITER_COLOURS = {"minmod": "tab:blue", "vanleer": "tab:orange", "mc": "tab:green", "none": "tab:red"}
PRECISION_MARKERS = {"float": "o", "double": "s"}
CFL_SIZES = {0.25: 18, 0.4: 34, 0.5: 55}
PPC_COLOURS = {1: "tab:blue", 4: "tab:orange", 9: "tab:green"}
UNITS = {"ritter": "m^2", "stoker": "m^2", "thacker": "m^3", "mangeney": "m^2"}
TITLES = {
    "ritter": "Ritter dam break (dry bed), t = 4 s",
    "stoker": "Stoker dam break (hR = 0.1 m), t = 4 s",
    "thacker": "Thacker planar oscillation, one period",
    "mangeney": "Mangeney granular dam break (two-phase, dry), t = 3 s",
}


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def read_rows(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            for r in csv.DictReader(f):
                for k in ("n", "dx_m", "cfl", "E_Pa", "wave_speed_m_s", "ppc", "cells", "particles", "l1", "rel_l1",
                          "front_m", "front_exact_m", "front_change", "field_change", "steps", "wall_s",
                          "updates_per_s"):
                    r[k] = num(r.get(k))
                r["source"] = p  # changes are relative to the stiffest run of the same invocation (file)
                rows.append(r)
    return rows


def pareto(runs):
    """Runs not dominated in (wall time, error), sorted by wall time."""
    front, best = [], math.inf
    for r in sorted(runs, key=lambda r: (r["wall_s"], r["l1"])):
        if r["l1"] < best:
            front.append(r)
            best = r["l1"]
    return front


def plot_case(name, runs, image_dir):
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    for r in runs:
        ax.scatter(r["wall_s"], r["l1"], c=LIMITER_COLOURS.get(r["limiter"], "k"),
                   marker=PRECISION_MARKERS.get(r["precision"], "x"), s=CFL_SIZES.get(round(r["cfl"], 2), 30),
                   alpha=0.75, edgecolors="none")
    front = pareto(runs)
    ax.plot([r["wall_s"] for r in front], [r["l1"] for r in front], "k-", lw=1.2, zorder=0, label="Pareto front")
    ax.scatter([r["wall_s"] for r in front], [r["l1"] for r in front], facecolors="none", edgecolors="k", s=90,
               lw=1.0)
    for r in front:
        ax.annotate("%d" % r["n"], (r["wall_s"], r["l1"]), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the stepping loop [s]")
    ax.set_ylabel("L1 error of h [%s]" % UNITS.get(name, ""))
    ax.set_title(TITLES.get(name, name), fontsize=10)
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=l) for l, c in LIMITER_COLOURS.items()]
    handles += [plt.Line2D([], [], color="grey", marker=m, ls="", label=p) for p, m in PRECISION_MARKERS.items()]
    handles += [plt.Line2D([], [], color="grey", marker="o", ls="", markersize=math.sqrt(s), label="CFL %g" % c)
                for c, s in CFL_SIZES.items()]
    handles.append(plt.Line2D([], [], color="k", label="Pareto front (cells)"))
    ax.legend(handles=handles, fontsize=7, loc="lower left", ncol=2)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    out = os.path.join(image_dir, "pareto_%s.png" % name)
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    return out


def plot_particles(runs, image_dir):
    # The stiffness series at the default particle CFL 0.2 (other CFLs are the time-step control).
    runs = [r for r in runs if abs(r["cfl"] - 0.2) < 1e-9]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9.0, 3.8))
    for ppc, src in sorted({(int(r["ppc"]), r["source"]) for r in runs}):
        rs = sorted([r for r in runs if int(r["ppc"]) == ppc and r["source"] == src], key=lambda r: r["E_Pa"])
        E = [r["E_Pa"] for r in rs]
        colour = PPC_COLOURS.get(ppc, "k")
        changed = [r for r in rs if r["field_change"] > 0]  # the reference run itself has no change
        a1.plot([r["E_Pa"] for r in changed], [r["field_change"] * 100 for r in changed], "o-", color=colour,
                label="thickness, %d/cell" % ppc)
        changed = [r for r in rs if r["front_change"] > 0]
        a1.plot([r["E_Pa"] for r in changed], [r["front_change"] * 100 for r in changed], "s--", color=colour,
                label="front, %d/cell" % ppc)
        a2.plot(E, [r["wall_s"] for r in rs], "o-", color=colour, label="%d/cell" % ppc)
    a1.axhline(1.0, color="k", lw=0.8, ls=":")
    for a in (a1, a2):
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("Young's modulus E [Pa]")
        a.grid(True, which="both", alpha=0.3)
    a1.set_ylabel("change against the stiffest run [%]")
    a2.set_ylabel("wall time [s]")
    a1.set_title("change against the stiffest run (1 % dotted)", fontsize=9)
    a2.set_title("particle dam break: cost, t = 3 s", fontsize=9)
    a1.legend(fontsize=6)
    a2.legend(fontsize=7)
    fig.tight_layout()
    out = os.path.join(image_dir, "pareto_particles.png")
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    return out


def markdown(grid, particles):
    for name in ("ritter", "stoker", "thacker", "mangeney"):
        runs = [r for r in grid if r["case"] == name]
        if not runs:
            continue
        print("\n**%s** (%d runs; L1 in %s)\n" % (TITLES.get(name, name), len(runs), UNITS[name]))
        print("| grid | limiter | precision | CFL | L1 | relative L1 | steps | wall time [s] | cell-updates/s |")
        print("| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
        for r in pareto(runs):
            print("| %s | %s | %s | %g | %.3e | %.2e | %d | %.3f | %.3g |" % (
                "%d²" % r["n"] if r["cells"] > r["n"] else "%d" % r["n"], r["limiter"], r["precision"], r["cfl"], r["l1"], r["rel_l1"], r["steps"], r["wall_s"],
                r["updates_per_s"]))
    if particles:
        print("\n**Particle dam break, stiffness** (change against the stiffest run of the same particles per cell)\n")
        print("| particles/cell | particle CFL | particles | E [Pa] | c [m/s] (given: Sound Speed) | sub-steps | speed-up (sub-steps) | wall time [s] | speed-up (wall) | "
              "front change | thickness change | L1 vs Mangeney (rel.) |")
        print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for ppc, src in sorted({(int(r["ppc"]), r["source"]) for r in particles}):
            rs = sorted([r for r in particles if int(r["ppc"]) == ppc and r["source"] == src],
                        key=lambda r: (-r["wave_speed_m_s"], r["cfl"]))
            ref, refSteps = rs[0]["wall_s"], rs[0]["steps"]
            for r in rs:
                print("| %d | %g | %d | %.0e | %.1f%s | %d | %.1f | %.2f | %.1f | %.2f %% | %.2f %% | %.3f |" % (
                    ppc, r["cfl"], r["particles"], r["E_Pa"], r["wave_speed_m_s"],
                    " (given)" if r["case"].endswith("_c") else "", r["steps"], refSteps / r["steps"], r["wall_s"], ref / r["wall_s"],
                    100 * r["front_change"], 100 * r["field_change"], r["rel_l1"]))


def main(argv):
    md = "--markdown" in argv
    args = [a for a in argv if a != "--markdown"]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 1
    image_dir, paths = args[0], args[1:]
    os.makedirs(image_dir, exist_ok=True)
    rows = read_rows(paths)
    grid = [r for r in rows if r["kind"] == "grid" and r["wall_s"] > 0 and r["l1"] > 0]
    particles = [r for r in rows if r["kind"] == "particles"]
    for name in sorted({r["case"] for r in grid}):
        print("wrote", plot_case(name, [r for r in grid if r["case"] == name], image_dir), file=sys.stderr)
    if particles:
        print("wrote", plot_particles(particles, image_dir), file=sys.stderr)
    if md:
        markdown(grid, particles)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
