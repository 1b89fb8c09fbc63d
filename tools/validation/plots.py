#!/usr/bin/env python3
"""Figures of the verification cases for docs/validation.md (tools/validation/make_report.sh).

Reads the CSVs the verification tests write when TALUS_VALIDATION_OUT is set
(tests/verification/ValidationOut.hpp, and column_collapse.csv of test_column_collapse.cpp) and
draws one PNG per case: numerical profiles against the analytic solution, and the error against the
cell size. A case whose CSVs are missing (its test did not run) is skipped with a message.

usage: plots.py CSV_DIR IMAGE_DIR
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

DPI = 80  # keeps each PNG well below 150 kB


def read(csv_dir, name):
    """The CSV as a dict of column name -> list (floats where they parse), or None when missing."""
    path = os.path.join(csv_dir, name)
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    out = {}
    for key in rows[0]:
        col = []
        for r in rows:
            v = r[key]
            try:
                col.append(float(v))
            except (TypeError, ValueError):
                col.append(v)
        out[key] = col
    return out


def save(fig, image_dir, name):
    for ax in fig.axes:
        dx = getattr(ax, "talus_dx", None)
        if dx:  # ticks at the cell sizes only (the default minor labels of a short log axis overlap)
            ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(dx))
            ax.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter(["%g" % d for d in dx]))
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    path = os.path.join(image_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print("plots.py: wrote", path)


def windowed(table, column):
    """The column where the exact solution holds (in_window = 1), NaN elsewhere (not drawn)."""
    return [v if w == 1 else float("nan") for v, w in zip(table[column], table["in_window"])]


def convergence(ax, dx, err, label, marker="o"):
    ax.loglog(dx, err, marker + "-", label=label)
    ax.talus_dx = dx  # save() puts the x ticks at the cell sizes


def order_guide(ax, dx, err, order, text):
    """A dashed line of the given slope through the finest point."""
    x0, y0 = dx[-1], err[-1]
    xs = [x0, dx[0]]
    ax.loglog(xs, [y0 * (x / x0) ** order for x in xs], "k--", lw=0.8, label=text)


def dambreak(csv_dir, image_dir, case, title, with_u):
    errors = read(csv_dir, case + "_errors.csv")
    fine = read(csv_dir, case + "_profile_nx800.csv")
    coarse = read(csv_dir, case + "_profile_nx100.csv")
    if errors is None or fine is None or coarse is None:
        print("plots.py: no CSVs for", case, "- skipped")
        return
    ncols = 3 if with_u else 2
    fig, axes = plt.subplots(1, ncols, figsize=(4 * ncols, 3.4))
    ax = axes[0]
    ax.plot(fine["x_m"], fine["h_exact_m"], "k-", lw=1.2, label="exact (cell averages)")
    ax.plot(coarse["x_m"], coarse["h_m"], "o", ms=2.5, label="100 cells")
    ax.plot(fine["x_m"], fine["h_m"], "-", lw=0.9, label="800 cells")
    first = read(csv_dir, case + "_first_profile_nx800.csv")
    if first is not None:
        ax.plot(first["x_m"], first["h_m"], ":", lw=1.0, label="800 cells, first order")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("h [m]")
    ax.set_xlim(30, 85)
    ax.set_title(title + ", t = 4 s")
    ax.legend(fontsize=7)
    if with_u:
        ax = axes[1]
        ax.plot(fine["x_m"], fine["u_exact_m_s"], "k-", lw=1.2, label="exact")
        ax.plot(coarse["x_m"], coarse["u_m_s"], "o", ms=2.5, label="100 cells")
        ax.plot(fine["x_m"], fine["u_m_s"], "-", lw=0.9, label="800 cells")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("u [m/s]")
        ax.set_xlim(30, 85)
        ax.legend(fontsize=7)
    ax = axes[-1]
    convergence(ax, errors["dx_m"], errors["l1_h_m2"], "L1(h) [m²]")
    if with_u:
        convergence(ax, errors["dx_m"], errors["l1_u_m2_s"], "L1(u) [m²/s]", "s")
    order_guide(ax, errors["dx_m"], errors["l1_h_m2"], 1.0, "order 1")
    fo = read(csv_dir, case + "_first_order.csv")
    if fo is not None:
        ax.loglog([errors["dx_m"][-1]], fo["l1_h_first_order_m2"], "rx", label="first order, 800 cells")
    ax.set_xlabel("dx [m]")
    ax.set_title("L1 error")
    ax.legend(fontsize=7)
    save(fig, image_dir, case + ".png")


def thacker(csv_dir, image_dir):
    errors = read(csv_dir, "thacker_errors.csv")
    profiles = [(n, read(csv_dir, "thacker_profile_n%d.csv" % n)) for n in (50, 100, 200)]
    if errors is None or any(p is None for _, p in profiles):
        print("plots.py: no CSVs for thacker - skipped")
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    ax = axes[0]
    fine = profiles[-1][1]
    ax.plot(fine["x_m"], fine["bed_m"], color="0.5", lw=1, label="bed")
    surf = [b + h for b, h in zip(fine["bed_m"], fine["h_exact_m"])]
    ax.plot(fine["x_m"], [s if h > 0 else float("nan") for s, h in zip(surf, fine["h_exact_m"])], "k-", lw=1.2,
            label="exact surface, t = T")
    for n, p in profiles:
        s = [b + h if h > 1e-6 else float("nan") for b, h in zip(p["bed_m"], p["h_m"])]
        ax.plot(p["x_m"], s, "-" if n == 200 else "o", ms=2.5, lw=0.9, label="%d² cells" % n)
    ax.set_ylim(-0.11, 0.06)
    ax.set_xlabel("x [m] (row through the vertex)")
    ax.set_ylabel("surface [m]")
    ax.set_title("Thacker, after one period")
    ax.legend(fontsize=7)
    ax = axes[1]
    convergence(ax, errors["dx_m"], errors["l1_h_m3"], "L1(h) [m³]")
    convergence(ax, errors["dx_m"], errors["centre_error_m"], "centre of mass [m]", "s")
    order_guide(ax, errors["dx_m"], errors["centre_error_m"], 2.0, "order 2")
    ax.set_xlabel("dx [m]")
    ax.set_title("errors")
    ax.legend(fontsize=7)
    save(fig, image_dir, "thacker.png")


def lake(csv_dir, image_dir):
    table = read(csv_dir, "lake_at_rest.csv")
    prof = read(csv_dir, "lake_at_rest_profile.csv")
    if table is None or prof is None:
        print("plots.py: no CSVs for the lake at rest - skipped")
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.2), gridspec_kw={"width_ratios": [1, 1.3]})
    ax = axes[0]
    ax.fill_between(prof["x_m"], prof["bed_m"], prof["surface_m"], color="#7fb6e6", step="mid", label="water")
    ax.step(prof["x_m"], prof["bed_m"], where="mid", color="0.3", lw=1, label="bed")
    ax.set_xlabel("x [m] (middle row)")
    ax.set_ylabel("elevation [m]")
    ax.set_title("lake at rest over a rough DEM")
    ax.legend(fontsize=7)
    ax = axes[1]
    labels = ["%s %s" % (d, l) for d, l in zip(table["depth_pressure"], table["limiter"])]
    for prec, colour in (("double", "C0"), ("float", "C1")):
        idx = [k for k, p in enumerate(table["precision"]) if p == prec]
        ax.semilogy([labels[k] for k in idx], [max(table["max_speed_m_s"][k], 1e-18) for k in idx], "o",
                    color=colour, label=prec)
    ax.set_ylabel("max |u| after 200 steps [m/s]")
    ax.tick_params(axis="x", labelrotation=60, labelsize=7)
    ax.legend(fontsize=7)
    save(fig, image_dir, "lake_at_rest.png")


def mangeney(csv_dir, image_dir):
    data = {m: (read(csv_dir, "mangeney_%s_errors.csv" % m), read(csv_dir, "mangeney_%s_profile_nx100.csv" % m),
                read(csv_dir, "mangeney_%s_profile_nx800.csv" % m)) for m in ("cos2", "cos4")}
    if any(v is None for vals in data.values() for v in vals):
        print("plots.py: no CSVs for Mangeney - skipped")
        return
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.4))
    for ax, m in zip(axes[:2], ("cos2", "cos4")):
        _, coarse, fine = data[m]
        ax.plot(fine["x_m"], windowed(fine, "hs_exact_m"), "k-", lw=1.2, label="exact (Mangeney 2000)")
        ax.plot(coarse["x_m"], coarse["hs_m"], "o", ms=2.5, label="100 cells")
        ax.plot(fine["x_m"], fine["hs_m"], "-", lw=0.9, label="800 cells")
        ax.axvline(17.0, color="0.6", ls=":", lw=1)
        ax.set_xlabel("x downslope [m]")
        ax.set_ylabel("h_s [m]")
        ax.set_title("%s, t = 3 s (exact right of the dotted line)" % m, fontsize=9)
        ax.legend(fontsize=7)
    ax = axes[2]
    for m, mk in (("cos2", "o"), ("cos4", "s")):
        e = data[m][0]
        convergence(ax, e["dx_m"], e["l1_h_m2"], "L1 %s [m²]" % m, mk)
    order_guide(ax, data["cos2"][0]["dx_m"], data["cos2"][0]["l1_h_m2"], 1.0, "order 1")
    ax.set_xlabel("dx [m]")
    ax.set_title("L1 error over [17, 50] m")
    ax.legend(fontsize=7)
    save(fig, image_dir, "mangeney.png")


def grid_block(csv_dir, image_dir):
    tags = [t for t in ("35_20", "30_15", "40_25") if read(csv_dir, "grid_block_series_%s.csv" % t) is not None]
    pile = [(dx, read(csv_dir, "pile_profile_dx%s.csv" % dx)) for dx in ("0.02", "0.01")]
    pile_err = read(csv_dir, "pile_errors.csv")
    if not tags and pile_err is None:
        print("plots.py: no CSVs for the rigid block / pile - skipped")
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.3))
    ax = axes[0]
    for t in tags:
        s = read(csv_dir, "grid_block_series_%s.csv" % t)
        th, de = t.split("_")
        ax.plot(s["t_s"], s["travel_exact_m"], "k-", lw=1)
        ax.plot(s["t_s"][::8], s["travel_m"][::8], "o", ms=3, label="θ %s°, δ %s°" % (th, de))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("centroid travel [m]")
    ax.set_title("rigid block (grid), lines: a t²/2")
    ax.legend(fontsize=7)
    ax = axes[1]
    for dx, p in pile:
        if p is None:
            continue
        ax.plot(p["x_m"], p["hs_final_m"], "-", lw=1, label="at rest, dx %s m" % dx)
    if pile[0][1] is not None:
        ax.plot(pile[0][1]["x_m"], pile[0][1]["hs_initial_m"], ":", color="0.4", label="initial")
    if pile_err is not None and pile[-1][1] is not None:
        p = pile[-1][1]
        top = max(p["hs_final_m"])
        xc = p["x_m"][p["hs_final_m"].index(top)]
        s = pile_err["repose_slope"][0]
        ax.plot([xc - top / s, xc, xc + top / s], [0, top, 0], "k--", lw=0.8, label="repose slope tan δ")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("h_s [m]")
    ax.set_title("pile, δ = φ = 30°")
    ax.legend(fontsize=7)
    save(fig, image_dir, "grid_block_pile.png")


def particle_block(csv_dir, image_dir):
    tags = [t for t in ("35_20", "30_15", "20_30") if read(csv_dir, "particle_block_series_%s.csv" % t) is not None]
    if not tags:
        print("plots.py: no CSVs for the particle block - skipped")
        return
    fig, ax = plt.subplots(figsize=(5.5, 3.3))
    for t in tags:
        s = read(csv_dir, "particle_block_series_%s.csv" % t)
        th, de = t.split("_")
        ax.plot(s["t_s"], s["v_exact_m_s"], "k-", lw=1)
        ax.plot(s["t_s"], s["v_mean_m_s"], "o", ms=3.5, label="θ %s°, δ %s°" % (th, de))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("mean particle velocity [m/s]")
    ax.set_title("sliding block (particles), lines: v = a t")
    ax.legend(fontsize=7)
    save(fig, image_dir, "particle_block.png")


def particle_dambreak(csv_dir, image_dir):
    p = read(csv_dir, "particle_dambreak_profile.csv")
    if p is None:
        print("plots.py: no CSVs for the particle dam break - skipped")
        return
    fig, ax = plt.subplots(figsize=(6, 3.3))
    fine = read(csv_dir, "mangeney_cos2_profile_nx800.csv")
    if fine is not None:
        ax.plot(fine["x_m"], windowed(fine, "hs_exact_m"), "k-", lw=1.2, label="exact (Mangeney 2000)")
    else:
        ax.step(p["x_m"], p["h_exact_m"], "k-", where="mid", label="exact (1 m columns)")
    ax.step(p["x_m"], p["h_particles_m"], "-", where="mid", label="particles (1 m columns)")
    grid = read(csv_dir, "mangeney_cos2_profile_nx100.csv")
    if grid is not None:
        ax.plot(grid["x_m"], grid["hs_m"], "--", lw=1, label="grid mode, dx 0.5 m")
    ax.axvline(17.0, color="0.6", ls=":", lw=1)
    ax.set_xlabel("x downslope [m] (exact solution right of the dotted line)")
    ax.set_ylabel("h [m]")
    ax.set_title("granular dam break: particles vs exact vs grid, t = 3 s", fontsize=10)
    ax.legend(fontsize=7)
    save(fig, image_dir, "particle_dambreak.png")


def particle_cut(csv_dir, image_dir):
    e = read(csv_dir, "cut_errors.csv")
    if e is None:
        print("plots.py: no CSVs for the vertical cut - skipped")
        return
    fig, axes = plt.subplots(1, len(e["case"]), figsize=(4.2 * len(e["case"]) + 0.8, 3.8))
    sc = None
    for ax, case, H, f in zip(axes, e["case"], e["H_m"], e["file"]):
        p = read(csv_dir, f)
        if p is None:
            continue
        sc = ax.scatter(p["x_m"], p["y_m"], c=p["cohesion_fraction"], s=3, vmin=0, vmax=1, cmap="RdYlGn")
        ax.add_patch(plt.Rectangle((8, 8), 4, 4, fill=False, ls="--", lw=0.8, color="0.3"))
        ax.set_aspect("equal")
        ax.set_xlim(2, 18)
        ax.set_ylim(2, 18)
        ax.set_title("H = %.2f m: %s" % (H, case), fontsize=9)
        ax.set_xlabel("x [m]")
    axes[0].set_ylabel("y [m]")
    if sc is not None:
        fig.colorbar(sc, ax=list(axes), label="cohesion fraction c/c0", shrink=0.9)
    fig.suptitle("vertical cut after 2 s (dashed: the initial column)", fontsize=9)
    path = os.path.join(image_dir, "particle_cut.png")
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print("plots.py: wrote", path)


def column_collapse(csv_dir, image_dir):
    sh = read(csv_dir, "column_collapse.csv")
    if sh is None:
        print("plots.py: no column_collapse.csv - skipped")
        return
    fig, ax = plt.subplots(figsize=(6, 3.6))
    a = [x / 10 for x in range(3, 121)]
    ax.loglog([x for x in a if x <= 1.8], [1.2 * x for x in a if x <= 1.8], "k-", lw=1.2,
              label="Lube 2005: 1.2 a (a ≲ 1.8)")
    ax.loglog([x for x in a if x >= 2.8], [1.9 * x ** (2 / 3) for x in a if x >= 2.8], "k--", lw=1.2,
              label="Lube 2005: 1.9 a^(2/3) (a ≳ 2.8)")
    for lo, hi in ((0.3, 1.8), (2.8, 12)):
        xs = [x for x in a if lo <= x <= hi]
        f = (lambda x: 1.2 * x) if hi < 2 else (lambda x: 1.9 * x ** (2 / 3))
        ax.fill_between(xs, [0.85 * f(x) for x in xs], [1.15 * f(x) for x in xs], color="0.85")
    ax.loglog(sh["a"], sh["relative_runout"], "o", label="Talus, Savage-Hutter K")
    k1 = read(csv_dir, "column_collapse_k1.csv")
    if k1 is not None:
        ax.loglog(k1["a"], k1["relative_runout"], "s", mfc="none", label="Talus, K = 1")
    ax.set_xlabel("aspect ratio a = H0 / d_i")
    ax.set_ylabel("(d∞ − d_i) / d_i")
    ax.set_title("granular column collapse (grey: ±15 %)")
    ax.legend(fontsize=7)
    save(fig, image_dir, "column_collapse.png")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    csv_dir, image_dir = sys.argv[1], sys.argv[2]
    os.makedirs(image_dir, exist_ok=True)
    dambreak(csv_dir, image_dir, "ritter", "Ritter", False)
    dambreak(csv_dir, image_dir, "stoker", "Stoker", True)
    thacker(csv_dir, image_dir)
    lake(csv_dir, image_dir)
    mangeney(csv_dir, image_dir)
    grid_block(csv_dir, image_dir)
    particle_block(csv_dir, image_dir)
    particle_dambreak(csv_dir, image_dir)
    particle_cut(csv_dir, image_dir)
    column_collapse(csv_dir, image_dir)


if __name__ == "__main__":
    main()
