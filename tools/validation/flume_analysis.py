#!/usr/bin/env python3
"""Damage and energy of a flume run (issue 18, item 4): what the run itself says about its crack.

  flume_analysis.py OUTPUT_DIR SCENE_DIR [--figure PNG] [--label TEXT]

OUTPUT_DIR is a `talus run` output of data/paper_flume_c18 or c26 (its particles/ layers,
particles_final.gpkg and diagnostics.csv); SCENE_DIR the scene (its dem.tif gives the raster's
origin through `gdalinfo`). The flume's geometry comes from tools/make_paper_scenes.py, which made
the scenes.

Printed (Markdown):
- damage at the end: mass-weighted mean c/c0 and the particle shares weakened (c/c0 < 0.99), below
  half (< 0.5) and broken (< 0.1), as docs/scenes.md counts them;
- the crack: the damaged particles (c/c0 < 0.5) connected to the obstacle's inner upslope corner
  (neighbours within LINK m, seeds within SEED m of the corner) and their reach from it; the same
  for the plastically sheared particles (plastic strain > PLASTIC), since with a dilatancy angle
  of 0 pure shear yields without degrading the bonds (spec P.26); and both along the line of the
  obstacle's inner edge in the block's own frame (the block turns about the obstacle);
- damage per report layer (when it happened);
- the energy budget from diagnostics.csv: potential energy released, peak kinetic energy (the
  impact), the work of basal friction and wall contacts, the artificial viscosity's dissipation
  and the artificial stress's work, and the remainder, which is what the elastic and plastic
  stresses took (plus landing losses).
With --figure (needs matplotlib) the final particles coloured by c/c0 and by plastic strain.
"""
import argparse
import ast
import csv
import math
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "validation"))
from particle_layers import read_particle_layer  # noqa: E402


def flume_constants():
    """The FL_* constants of tools/make_paper_scenes.py, read without importing it (it needs GDAL)."""
    tree = ast.parse((ROOT / "tools" / "make_paper_scenes.py").read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.Assign):
            names = [t.id for t in node.targets if isinstance(t, ast.Name)] or [
                e.id for t in node.targets if isinstance(t, ast.Tuple) for e in t.elts]
            if not any(n.startswith("FL_") for n in names):
                continue
            try:
                value = ast.literal_eval(node.value)
            except ValueError:
                continue
            if len(names) == 1:
                out[names[0]] = value
            else:
                out.update(zip(names, value))
    return argparse.Namespace(**out)


scenes = flume_constants()

WEAK, HALF, BROKEN = 0.99, 0.5, 0.1  # c/c0 classes of docs/scenes.md
LINK = 0.012   # m: particles closer than this are neighbours (spacing 5 mm at 4 per 1 cm cell)
SEED = 0.03    # m: damaged particles this close to the corner start the crack
PLASTIC = 0.01  # plastic strain of the shear band
BAND = 0.01    # m: half-width of the band along the obstacle's inner edge (two particle spacings)


def read_layer(gpkg):
    """Per particle: x, y, mass, c/c0, plastic strain, speed."""
    cols = ("mass", "cohesion_fraction", "plastic_strain", "speed")
    return [dict(x=x, y=y, m=m, c=c, p=p, v=v) for x, y, m, c, p, v in read_particle_layer(gpkg, cols)]


def raster_frame(dem):
    """(west x, north y, columns, rows, cell size) of the scene's DEM, from gdalinfo."""
    info = subprocess.run(["gdalinfo", str(dem)], capture_output=True, text=True, check=True).stdout
    nx, ny = map(int, re.search(r"Size is (\d+), (\d+)", info).groups())
    x0, y0 = map(float, re.search(r"Origin = \(([-\d.e+]+),([-\d.e+]+)\)", info).groups())
    dx = float(re.search(r"Pixel Size = \(([-\d.e+]+),", info).group(1))
    return x0, y0, nx, ny, dx


def geometry(scene_dir):
    """The obstacle's inner upslope corner and its rectangle, in world coordinates."""
    x0, y0, nx, ny, dx = raster_frame(scene_dir / "dem.tif")
    yc = y0 - ny * dx / 2  # the channel's centre line (the raster's middle row)
    x_break = x0 + scenes.FL_L_INCLINE * math.cos(math.radians(scenes.FL_INCLINE))
    _h, ol, ow = scenes.FL_OBST
    bw = scenes.FL_BLOCK[2]
    # make_paper_scenes.py's across coordinate Y grows with the row index, and rows run from north to
    # south: its obstacle at Y in [bw/2 - ow, bw/2) lies at world y in (yc - bw/2, yc - bw/2 + ow].
    rect = (x_break, yc - bw / 2, ol, ow)  # x, y of the lower-left corner, length, width
    return dict(corner=(x_break, yc - bw / 2 + ow), rect=rect, yc=yc)


def connected_reach(pts, corner, damaged):
    """The damaged particles connected to the corner: (count, largest distance from the corner)."""
    cx, cy = corner
    idx = [k for k, q in enumerate(pts) if damaged(q)]
    cell = {}
    for k in idx:
        cell.setdefault((int(pts[k]["x"] // LINK), int(pts[k]["y"] // LINK)), []).append(k)
    seen = {k for k in idx if math.hypot(pts[k]["x"] - cx, pts[k]["y"] - cy) < SEED}
    stack = list(seen)
    while stack:
        k = stack.pop()
        gx, gy = int(pts[k]["x"] // LINK), int(pts[k]["y"] // LINK)
        for a in (gx - 1, gx, gx + 1):
            for b in (gy - 1, gy, gy + 1):
                for n in cell.get((a, b), []):
                    if n not in seen and math.hypot(pts[n]["x"] - pts[k]["x"], pts[n]["y"] - pts[k]["y"]) < LINK:
                        seen.add(n)
                        stack.append(n)
    if not seen:
        return 0, 0.0
    return len(seen), max(math.hypot(pts[k]["x"] - cx, pts[k]["y"] - cy) for k in seen)


def block_frame(pts):
    """The block's own frame from the particle cloud (robust centre, principal axes): e1 along its
    length (the larger extent: 0.3 m against 0.25 m), pointing downslope, e2 = e1 turned by +90
    degrees. Returns (centre, e1, e2) or None for a cloud that no longer has a clear long axis."""
    xs = sorted(q["x"] for q in pts)
    ys = sorted(q["y"] for q in pts)
    mx, my = xs[len(xs) // 2], ys[len(ys) // 2]
    core = [q for q in pts if math.hypot(q["x"] - mx, q["y"] - my) < 0.3]  # drops particles flung away
    cx = sum(q["x"] for q in core) / len(core)
    cy = sum(q["y"] for q in core) / len(core)
    sxx = sum((q["x"] - cx) ** 2 for q in core)
    syy = sum((q["y"] - cy) ** 2 for q in core)
    sxy = sum((q["x"] - cx) * (q["y"] - cy) for q in core)
    angle = 0.5 * math.atan2(2 * sxy, sxx - syy)  # direction of the largest variance
    e1 = (math.cos(angle), math.sin(angle))
    if e1[0] < 0:
        e1 = (-e1[0], -e1[1])
    return (cx, cy), e1, (-e1[1], e1[0])


def corner_line_profile(pts, geo):
    """Damage and plastic strain along the line of the obstacle's inner edge, in the block's frame:
    the band of particles within BAND of the line n = n_c (the obstacle covered the block's -y side
    up to n_c = -(block width / 2 - obstacle width) before the block turned), binned by the position
    s along the block's length (front at +length/2); and the mirrored band n = -n_c on the free side
    as a control."""
    (cx, cy), e1, e2 = block_frame(pts)
    bw, ow = scenes.FL_BLOCK[2], scenes.FL_OBST[2]
    n_c = -(bw / 2 - ow)
    rows = []
    half = scenes.FL_BLOCK[1] / 2
    nbins = 6
    for b in range(nbins):
        s0 = half - (b + 1) * (2 * half / nbins)
        s1 = s0 + 2 * half / nbins
        line, ctrl = [], []
        for q in pts:
            s = (q["x"] - cx) * e1[0] + (q["y"] - cy) * e1[1]
            n = (q["x"] - cx) * e2[0] + (q["y"] - cy) * e2[1]
            if s0 <= s < s1:
                if abs(n - n_c) < BAND:
                    line.append(q)
                elif abs(n + n_c) < BAND:
                    ctrl.append(q)
        rows.append((s0, s1, line, ctrl))
    return math.degrees(math.atan2(e1[1], e1[0])), rows


def damage(pts):
    mass = sum(q["m"] for q in pts)
    n = len(pts)
    return dict(mean=sum(q["m"] * q["c"] for q in pts) / mass, weak=sum(q["c"] < WEAK for q in pts) / n,
                half=sum(q["c"] < HALF for q in pts) / n, broken=sum(q["c"] < BROKEN for q in pts) / n,
                plastic=sum(q["p"] > PLASTIC for q in pts) / n)


def energy(diag_csv):
    rows = list(csv.DictReader(open(diag_csv)))
    peak = max(rows, key=lambda r: float(r["particle_kinetic_J"]))
    last = rows[-1]
    f = lambda r, k: float(r[k])  # noqa: E731
    released = f(last, "particle_potential_released_J")
    ke, fric = f(last, "particle_kinetic_J"), f(last, "particle_friction_work_J")
    visc, art = f(last, "particle_viscous_dissipation_J"), f(last, "particle_art_stress_work_J")
    out = dict(t_end=f(last, "time_s"), peak_ke=f(peak, "particle_kinetic_J"), t_peak=f(peak, "time_s"),
               released=released, ke=ke, friction=fric, viscous=visc, art=art,
               rest=released - ke - fric - visc + art)
    # The impact: from the peak of the kinetic energy to the end, each term's change.
    keys = ("particle_potential_released_J", "particle_kinetic_J", "particle_friction_work_J",
            "particle_viscous_dissipation_J", "particle_art_stress_work_J")
    d = {k: f(last, k) - f(peak, k) for k in keys}
    out["impact"] = dict(released=d[keys[0]], ke_lost=-d[keys[1]], friction=d[keys[2]], viscous=d[keys[3]],
                         art=d[keys[4]],
                         rest=d[keys[0]] - d[keys[1]] - d[keys[2]] - d[keys[3]] + d[keys[4]])
    return out


def figure(pts, geo, path, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    cx, cy = geo["corner"]
    xs = [q["x"] - cx for q in pts]
    ys = [q["y"] - geo["yc"] for q in pts]
    # Plastic strain on a scale up to its 95th percentile (a few squeezed-out particles reach 10-20).
    plastic = sorted(q["p"] for q in pts)
    p95 = max(plastic[int(0.95 * (len(plastic) - 1))], 1e-6)
    for ax, key, title, cmap, vmax in ((axes[0], "c", "c / c0", "inferno", 1.0),
                                       (axes[1], "p", f"plastic strain (scale to its 95th percentile)", "viridis", p95)):
        vals = [q[key] for q in pts]
        sc = ax.scatter(xs, ys, c=vals, s=4, cmap=cmap, vmin=0, vmax=vmax)
        x, y, length, width = geo["rect"]
        ax.add_patch(Rectangle((x - cx, y - geo["yc"]), length, width, fill=False, ec="k", lw=1.2))
        ax.set_xlim(-0.3, 0.2)
        ax.set_ylim(-0.2, 0.25)
        ax.set_aspect("equal")
        ax.set_xlabel("x from the slope break [m] (downslope)")
        ax.set_ylabel("y from the channel centre [m]")
        outside = sum(not (-0.3 <= x <= 0.2 and -0.2 <= y <= 0.25) for x, y in zip(xs, ys))
        ax.set_title(f"{label}: {title}" + (f"\n({outside} particles beyond the frame)" if outside else ""),
                     fontsize=9)
        fig.colorbar(sc, ax=ax, shrink=0.8)
    fig.savefig(path, dpi=90)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("output", type=pathlib.Path)
    ap.add_argument("scene", type=pathlib.Path)
    ap.add_argument("--figure", type=pathlib.Path)
    ap.add_argument("--label", default="flume")
    a = ap.parse_args()
    geo = geometry(a.scene)
    final = read_layer(a.output / "particles_final.gpkg")
    d = damage(final)
    block_len = scenes.FL_BLOCK[1]
    print(f"### {a.label}\n")
    print("| mean c/c0 | weakened (< 0.99) | below half | broken (< 0.1) | plastic strain > 0.01 |")
    print("|---|---|---|---|---|")
    print(f"| {d['mean']:.3f} | {100 * d['weak']:.1f} % | {100 * d['half']:.1f} % | {100 * d['broken']:.1f} % | "
          f"{100 * d['plastic']:.1f} % |\n")
    for name, test in (("damaged (c/c0 < 0.5)", lambda q: q["c"] < HALF),
                       ("sheared (plastic strain > 0.01)", lambda q: q["p"] > PLASTIC)):
        n, dist = connected_reach(final, geo["corner"], test)
        print(f"- {name}, connected to the obstacle's inner corner: {n} particles, reaching {100 * dist:.1f} cm "
              f"from it (the block is {100 * block_len:.0f} cm long; its frame: the table below)")
    turn, rows = corner_line_profile(final, geo)
    print(f"\nAlong the obstacle's inner edge, in the block's frame (the block turned by {turn:.0f} degrees;"
          f" s from its front, bins of {100 * (rows[0][1] - rows[0][0]):.0f} cm; band of +-{100 * BAND:.0f} cm;"
          " control: the mirrored band on the free side):\n")
    print("| s from the front (cm) | particles | mean c/c0 | max plastic strain | control mean c/c0 | control max plastic strain |")
    print("|---|---|---|---|---|---|")
    front = rows[0][1]
    for s0, s1, line, ctrl in rows:
        mean = lambda v: sum(v) / len(v) if v else float("nan")  # noqa: E731
        print(f"| {100 * (front - s1):.0f}-{100 * (front - s0):.0f} | {len(line)} | {mean([q['c'] for q in line]):.3f} | "
              f"{max([q['p'] for q in line], default=float('nan')):.3f} | {mean([q['c'] for q in ctrl]):.3f} | "
              f"{max([q['p'] for q in ctrl], default=float('nan')):.3f} |")
    print("\n| report | t (s) | mean c/c0 | weakened | broken | max speed (m/s) |")
    print("|---|---|---|---|---|---|")
    times = {}
    index_csv = a.output / "series" / "index.csv"
    if index_csv.exists():
        times = {int(r["index"]): float(r["time_s"]) for r in csv.DictReader(open(index_csv))}
    for layer in sorted((a.output / "particles").glob("particles_*.gpkg")):
        k = int(layer.stem.split("_")[1])
        pts = read_layer(layer)
        dk = damage(pts)
        print(f"| {k} | {times.get(k, float('nan')):.2f} | {dk['mean']:.3f} | {100 * dk['weak']:.1f} % | "
              f"{100 * dk['broken']:.1f} % | {max(q['v'] for q in pts):.2f} |")
    e = energy(a.output / "diagnostics.csv")
    print(f"\nEnergy to t = {e['t_end']:.2f} s: potential released {e['released']:.2f} J; peak kinetic energy "
          f"{e['peak_ke']:.2f} J at {e['t_peak']:.3f} s; basal friction and walls {e['friction']:.2f} J; artificial "
          f"viscosity {e['viscous']:.2f} J; artificial stress work {e['art']:.3f} J; kinetic energy left "
          f"{e['ke']:.3f} J; remainder (elastic and plastic work, landings) {e['rest']:.2f} J.")
    i = e["impact"]
    print(f"\nFrom the peak of the kinetic energy to the end (the impact and after): kinetic energy lost "
          f"{i['ke_lost']:.2f} J, potential released {i['released']:.2f} J; taken by basal friction and walls "
          f"{i['friction']:.2f} J, the artificial viscosity {i['viscous']:.2f} J, the elastic and plastic stresses "
          f"(remainder) {i['rest']:.2f} J; artificial stress work {i['art']:.3f} J.")
    if a.figure:
        figure(final, geo, a.figure, a.label)
        print(f"\nfigure: {a.figure}")


if __name__ == "__main__":
    main()
