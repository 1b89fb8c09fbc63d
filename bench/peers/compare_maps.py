#!/usr/bin/env python3
"""Metrics and the markdown report of the Talus / GeoClaw comparison.

  compare_maps.py WORK    reads WORK/runs.jsonl and the run folders, prints the tables and writes
                          WORK/results.md (and WORK/results.json with the numbers)

Definitions
  wall           median over the runs of the process wall time (s); `int.` = the code's own
                 figure (Talus summary.json wall_time_s, GeoClaw timing.txt total time)
  steps          time steps (Talus: SSP-RK2 steps of two stages each; GeoClaw: level-1 steps)
  max depth      Talus hfmax.tif (includes t = 0); GeoClaw fgmax (every step, cell value)
                 combined with the initial depth, so both include t = 0; nodata cells excluded
  inundated      max depth > 0.01 m; area = cells x dx^2
  rel L1(a, b)   sum|a - B| / sum|B|, B = reference b aggregated to a's grid by block mean
  agree 10 %     of the cells inundated in a or B, the fraction with |a - B| <= 0.1 B
"""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import geoclaw_cases as gc  # noqa: E402
import peers_io  # noqa: E402

WET = 0.01


def median(v):
    v = [x for x in v if x is not None]
    return float(np.median(v)) if v else None


def group_runs(recs):
    g = {}
    for r in recs:
        if r.get("rc") != 0:
            continue
        g.setdefault(r["key"], []).append(r)
    return g


def is_clean(r, limit=float(os.environ.get("PEERS_CONTENDED", "0.1"))):
    """Run not disturbed by other processes: others_share (their CPU during the run as a share of
    the machine) below the limit. Records without it (older runner): judged by cpu / wall."""
    if "others_share" in r:
        return r["others_share"] <= limit
    ratio = r.get("cpu_s", 0) / max(r["wall_s"], 1e-9)
    return ratio >= 0.95 if r["threads"] == 1 else ratio >= 1.6


def summarise(runs):
    clean = [r for r in runs if is_clean(r)]
    n_all = len(runs)
    if clean:
        runs = clean
    steps = sorted({r.get("steps") for r in runs})
    return dict(n=f"{len(clean)}/{n_all}", wall=median([r["wall_s"] for r in runs]),
                wall_min=min(r["wall_s"] for r in runs), wall_max=max(r["wall_s"] for r in runs),
                internal=median([r.get("internal_wall_s") for r in runs]),
                steps=steps[0] if len(steps) == 1 else steps, sim_s=runs[0].get("sim_s"),
                cpu=median([r.get("cpu_s") for r in runs]),
                busy=max(max(r.get("busy_before") or 0, r.get("others_share") or 0) for r in runs),
                out=runs[-1]["out_dir"],
                rec=runs[-1])


# ---------------------------------------------------------------------------------------------
# max-depth maps
# ---------------------------------------------------------------------------------------------
def hmax_map(work, key, s):
    """Max-depth map (rows from the top, NaN on nodata) of a run."""
    code, case = key.split("/")[0], key.split("/")[1]
    gdir = os.path.join(work, "grids", case.replace("kot_", ""))
    dem = gc.read_raster(os.path.join(gdir, "dem.tif"))
    if code == "talus":
        h = gc.read_raster(os.path.join(s["out"], "hfmax.tif")).values
    else:
        cdir = os.path.join(work, "geoclaw", case)
        h, _ = peers_io.read_fgmax(s["out"], dem.nx, dem.ny, dem.dx)
        h = np.maximum(np.nan_to_num(h), np.load(os.path.join(cdir, "target_h.npy")))
    h = np.where(np.isnan(dem.values), np.nan, np.nan_to_num(h))
    return h, dem.dx


def aggregate(b, f):
    if f == 1:
        return b
    ny, nx = b.shape[0] // f, b.shape[1] // f
    return b[: ny * f, : nx * f].reshape(ny, f, nx, f).mean(axis=(1, 3))


def distance(a, dxa, b, dxb):
    """rel L1 and agreement of map a against reference b (b on the same or a finer grid)."""
    f = int(round(dxa / dxb))
    B = aggregate(b, f)
    m = ~np.isnan(a) & ~np.isnan(B)
    A, B = a[m], B[m]
    l1 = float(np.abs(A - B).sum() / np.abs(B).sum())
    wet = (A > WET) | (B > WET)
    agree = float(np.mean(np.abs(A[wet] - B[wet]) <= 0.1 * B[wet])) if wet.any() else float("nan")
    return l1, agree


def map_stats(h, dx):
    wet = h > WET
    return dict(area_m2=float(wet.sum() * dx * dx), median_hmax=float(np.median(h[wet])) if wet.any() else 0.0,
                max_hmax=float(np.nanmax(h)))


def geoclaw_volumes(work, case, out):
    """Water volume of each output frame of a GeoClaw run (m3), nodata cells excluded."""
    dem = gc.read_raster(os.path.join(work, "grids", case.replace("kot_", ""), "dem.tif"))
    m = ~np.isnan(dem.values)
    vols = []
    f = 0
    while os.path.exists(os.path.join(out, "fort.t%04d" % f)):
        q, t = peers_io.read_frame(out, f, dem.nx, dem.ny, dem.dx)
        vols.append((t, float(np.nansum(q[0][m]) * dem.dx ** 2)))
        f += 1
    return vols


def geoclaw_topo_check(work, case, out):
    """max |B_GeoClaw - DEM| on data cells and max |h0_GeoClaw - water| (binary runs only)."""
    cdir = os.path.join(work, "geoclaw", case)
    zb = np.load(os.path.join(cdir, "target_topo.npy"))
    h0 = np.load(os.path.join(cdir, "target_h.npy"))
    meta = json.load(open(os.path.join(cdir, "case.json")))
    ny, nx, dx = meta["ny"], meta["nx"], meta["dx"]
    try:
        B = peers_io.read_aux(out, 0, nx, ny, dx)
        q, _ = peers_io.read_frame(out, 0, nx, ny, dx)
    except Exception as e:  # pragma: no cover
        return dict(error=str(e))
    return dict(topo_err=float(np.nanmax(np.abs(B - zb))), h0_err=float(np.nanmax(np.abs(q[0] - h0))))


# ---------------------------------------------------------------------------------------------
# Ritter
# ---------------------------------------------------------------------------------------------
def ritter_error(work, key, s):
    code, case = key.split("/")[0], key.split("/")[1]
    meta = json.load(open(os.path.join(work, "geoclaw", case, "case.json")))
    nx, ny, dx = meta["nx"], meta["ny"], meta["dx"]
    if code == "talus":
        h = gc.read_raster(os.path.join(s["out"], "hffinal.tif")).values
    else:
        q, t = peers_io.read_frame(s["out"], 1, nx, ny, dx)
        if abs(t - gc.RITTER_T) > 1e-9:
            raise SystemExit(f"{s['out']}: frame 1 is at t = {t}")
        h = q[0]
    row_spread = float(np.nanmax(np.nanmax(h, axis=0) - np.nanmin(h, axis=0)))
    hm = np.nanmean(h, axis=0)
    ref = gc.ritter_cell_averages(nx, dx)
    return float(np.sum(np.abs(hm - ref)) * dx), row_spread


def loglog_interp(xs, ys, x):
    """Piecewise-linear interpolation of log y against log x; linear extrapolation from the end
    segments. Returns (y, extrapolated?)."""
    lx, ly = np.log(np.asarray(xs)), np.log(np.asarray(ys))
    o = np.argsort(lx)
    lx, ly = lx[o], ly[o]
    t = math.log(x)
    if len(lx) == 1:
        return float("nan"), True
    if t < lx[0] or t > lx[-1]:
        i = 0 if t < lx[0] else len(lx) - 2
        slope = (ly[i + 1] - ly[i]) / (lx[i + 1] - lx[i])
        return float(math.exp(ly[i] + slope * (t - lx[i]))), True
    return float(math.exp(np.interp(t, lx, ly))), False


# ---------------------------------------------------------------------------------------------
def fmt(v, spec):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if isinstance(v, list):
        return "/".join(format(x, spec) for x in v)
    return format(v, spec)


TALUS_LABEL = {"float": "Talus float, slope corr. on (default)", "double": "Talus double, slope corr. on",
               "float_sc0": "Talus float, slope corr. off", "double_sc0": "Talus double, slope corr. off",
               "float_sc0_split": "Talus float, slope corr. off, split sweeps (CFL 0.5)",
               "float_sc0_split_cfl09": "Talus float, slope corr. off, split sweeps, CFL 0.9 (draining)",
               "float_split_cfl09": "Talus float, split sweeps, CFL 0.9 (draining)",
               "geoclaw": "GeoClaw (dry tol. 1e-6 m, as Talus)",
               "geoclaw_dry1e-3": "GeoClaw (dry tol. 1e-3 m, its default)"}


def main():
    work = os.path.abspath(sys.argv[1])
    recs = peers_io_records(work)
    G = group_runs(recs)
    env = {}
    envp = os.path.join(work, "environment.json")
    if os.path.exists(envp):
        env = json.load(open(envp))
    grids = json.load(open(os.path.join(work, "grids", "grids.json"))) if os.path.exists(
        os.path.join(work, "grids", "grids.json")) else {}
    S = {k: summarise(v) for k, v in G.items()}
    lines = []
    out = dict(runs={k: {kk: vv for kk, vv in s.items() if kk != "rec"} for k, s in S.items()})
    P = lines.append

    P("# Talus vs GeoClaw: kot_dambreak, grid study, Ritter dam break")
    P("")
    if env:
        P("Talus: `%s` (snapshot of build/src/talus, commit %s%s); GeoClaw: clawpack %s, gfortran `%s`, "
          "`%s`. Machine: %s. Timings: process wall time and CPU time (user + system), medians over the "
          "runs that other processes did not disturb (n = undisturbed/all; disturbed: other processes used "
          "> 10 %% of the machine's CPU during the run; if no run is undisturbed, all are used); `busy` = "
          "the largest share of the machine's CPU other processes used before or during those runs." % (
              env.get("talus_bin"), env.get("git_commit"), " + local changes" if env.get("git_dirty") else "",
              env.get("clawpack"), env.get("fflags"), env.get("gfortran"), env.get("machine")))
        P("")

    # ---------------- kot_dambreak 5 m ----------------
    ref_key = "geoclaw/kot_r5/geoclaw/1t"
    maps = {}
    if ref_key in S:
        P("## kot_dambreak, 5 m (200 x 250 cells, 90 s, Manning 0.05, open boundaries)")
        P("")
        P("| code / configuration | threads | n | wall s (median) | cpu s | int. s | steps | steps per sim. s | "
          "inundated area m² | median max depth m | max depth m | rel L1 vs GeoClaw | agree 10 % vs GeoClaw | "
          "volume at 90 s m³ | busy |")
        P("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        href, dxr = hmax_map(work, ref_key, S[ref_key])
        rows = [k for k in S if "/kot_r5/" in k]
        order = ["float", "double", "float_sc0", "double_sc0", "float_sc0_split", "float_sc0_split_cfl09",
                 "float_sc0_hancock_cfl09", "float_hancock_cfl09", "geoclaw", "geoclaw_dry1e-3"]
        kot_vols = {}
        rows.sort(key=lambda k: (order.index(k.split("/")[2]), k.split("/")[3]))
        kot = {}
        for k in rows:
            s = S[k]
            h, dx = hmax_map(work, k, s)
            maps[k] = (h, dx)
            st = map_stats(h, dx)
            l1, ag = distance(h, dx, href, dxr)
            if k.startswith("talus"):
                vol = s["rec"].get("final_m3")
            else:
                vols = geoclaw_volumes(work, "kot_r5", s["out"])
                vol = vols[-1][1] if vols else None
                kot_vols[k] = vols
            sps = s["steps"] / s["sim_s"] if isinstance(s["steps"], int) else None
            cfg = k.split("/")[2]
            kot[k] = dict(st, rel_l1_vs_geoclaw=l1, agree_vs_geoclaw=ag, volume_end_m3=vol, wall=s["wall"],
                          steps=s["steps"])
            P(f"| {TALUS_LABEL[cfg]} | {k.split('/')[3][:-1]} | {s['n']} | {fmt(s['wall'], '.2f')} | "
              f"{fmt(s['cpu'], '.2f')} | {fmt(s['internal'], '.2f')} | {fmt(s['steps'], 'd')} | {fmt(sps, '.1f')} | "
              f"{st['area_m2']:.0f} | {st['median_hmax']:.3f} | {st['max_hmax']:.2f} | {l1:.3f} | {ag:.3f} | "
              f"{fmt(vol, '.0f')} | {fmt(s['busy'], '.2f')} |")
        out["kot_r5"] = kot
        P("")
        # GeoClaw checks and volume history
        chk = geoclaw_topo_check(work, "kot_r5", S[ref_key]["out"])
        vols = geoclaw_volumes(work, "kot_r5", S[ref_key]["out"])
        out["geoclaw_checks"] = dict(chk, volumes=vols)
        P("GeoClaw input check (frame 0): max |B − DEM| = %s m over the data cells, max |h0 − water.tif| = %s m "
          "(the topo/qinit construction in geoclaw_cases.py). GeoClaw steps over cfl_max: %s (largest CFL %s)." % (
              fmt(chk.get("topo_err"), ".2g"), fmt(chk.get("h0_err"), ".2g"),
              S[ref_key]["rec"].get("cfl_over_max"), S[ref_key]["rec"].get("max_cfl")))
        P("")
        P("Water volume in the domain (m³) every 15 s: GeoClaw from its frames, Talus from diagnostics.csv:")
        P("")
        P("| t s | " + " | ".join("%g" % t for t, _ in vols) + " |")
        P("|---|" + "---|" * len(vols) + "")
        for gk_, gv in sorted(kot_vols.items()):
            if gk_.endswith("/1t"):
                P(f"| {TALUS_LABEL[gk_.split('/')[2]]} | " + " | ".join("%.0f" % v for _, v in gv) + " |")
        for k in rows:
            if not k.startswith("talus") or not k.endswith("/1t"):
                continue
            import csv
            drows = list(csv.DictReader(open(os.path.join(S[k]["out"], "diagnostics.csv"))))
            vs = []
            for t, _ in vols:
                if t == 0:
                    vs.append(float(S[k]["rec"]["initial_m3"]))
                    continue
                r = min(drows, key=lambda r: abs(float(r["time_s"]) - t))
                vs.append(float(r["volume_m3"]))
            P(f"| {TALUS_LABEL[k.split('/')[2]]} | " + " | ".join("%.0f" % v for v in vs) + " |")
        P("")

    # ---------------- grid study ----------------
    gcfg = os.environ.get("PEERS_GRID_TALUS_CONFIG", "float_sc0")
    levels = sorted({k.split("/")[1] for k in S if k.split("/")[1].startswith("kot_r")},
                    key=lambda c: -float(c[5:].replace("p", ".")))
    if len(levels) > 1:
        finest = levels[-1]
        P(f"## Grid study (Talus: {TALUS_LABEL[gcfg]}; both codes on 1 thread; finest grid {finest[4:]})")
        P("")
        P("| code | grid | cells | n | wall s (median) | cpu s | steps | steps per sim. s | inundated area m² | "
          "median max depth m | rel L1 vs own finest | rel L1 vs other finest | agree 10 % own | "
          "agree 10 % other | initial volume m³ | volume at 90 s m³ | busy |")
        P("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        tk = lambda lev: f"talus/{lev}/{gcfg}/1t"  # noqa: E731
        gk = lambda lev: f"geoclaw/{lev}/geoclaw/1t"  # noqa: E731
        grid_out = {}
        fin = {}
        for code, kf in (("talus", tk), ("geoclaw", gk)):
            if kf(finest) in S:
                fin[code] = hmax_map(work, kf(finest), S[kf(finest)])
        for code, kf in (("talus", tk), ("geoclaw", gk)):
            other = "geoclaw" if code == "talus" else "talus"
            for lev in levels:
                k = kf(lev)
                if k not in S:
                    continue
                s = S[k]
                h, dx = hmax_map(work, k, s)
                st = map_stats(h, dx)
                own = distance(h, dx, *fin[code]) if code in fin and lev != finest else (None, None)
                oth = distance(h, dx, *fin[other]) if other in fin else (None, None)
                g = grids.get(lev.replace("kot_", ""), {})
                sps = s["steps"] / s["sim_s"] if isinstance(s["steps"], int) else None
                if code == "talus":
                    vend = s["rec"].get("final_m3")
                else:
                    gv = geoclaw_volumes(work, lev, s["out"])
                    vend = gv[-1][1] if gv else None
                grid_out[k] = dict(st, volume_end_m3=vend, wall=s["wall"], steps=s["steps"], l1_own=own[0],
                                   l1_other=oth[0], agree_own=own[1], agree_other=oth[1])
                P(f"| {code} | {g.get('dx', 0):.3f} m | {g.get('nx', 0)}x{g.get('ny', 0)} | {s['n']} | "
                  f"{fmt(s['wall'], '.2f')} | {fmt(s['cpu'], '.2f')} | {fmt(s['steps'], 'd')} | {fmt(sps, '.1f')} | "
                  f"{st['area_m2']:.0f} | {st['median_hmax']:.3f} | {fmt(own[0], '.3f')} | {fmt(oth[0], '.3f')} | "
                  f"{fmt(own[1], '.3f')} | {fmt(oth[1], '.3f')} | {fmt(g.get('volume_m3'), '.0f')} | "
                  f"{fmt(vend, '.0f')} | {fmt(s['busy'], '.2f')} |")
        out["grid"] = grid_out
        P("")
        P("The initial water differs between grids (the disc and h = max(0, 1959.83 − z) sampled on each "
          "grid), so each grid is its own discrete problem; the distances measure how far the coarse "
          "result is from the finest one, not a convergence order.")
        P("")

    # ---------------- Ritter ----------------
    rk = sorted({k for k in S if "/ritter_" in k})
    if rk:
        P("## Ritter dam break (2000 m channel, dam at 1000 m, h_L = 1 m, dry downstream, t = 50 s, "
          "4 cells wide, walls, no friction; 1 thread)")
        P("")
        P("| code | dx m | cells | n | wall s (median) | cpu s | steps | L1 error of h (m²) | rows spread m | busy |")
        P("|---|---|---|---|---|---|---|---|---|---|")
        rit = {}
        for k in sorted(rk, key=lambda k: (k.split("/")[2], -float(k.split("/")[1][9:].replace("p", ".")))):
            s = S[k]
            err, spread = ritter_error(work, k, s)
            meta = json.load(open(os.path.join(work, "geoclaw", k.split("/")[1], "case.json")))
            cfg = k.split("/")[2]
            rit[k] = dict(dx=meta["dx"], err=err, wall=s["wall"], cpu=s["cpu"], steps=s["steps"], cfg=cfg)
            P(f"| {TALUS_LABEL.get(cfg, cfg) if cfg.startswith('geoclaw') else 'Talus ' + cfg} | {meta['dx']:g} | "
              f"{meta['nx']}x{meta['ny']} | {s['n']} | {fmt(s['wall'], '.2f')} | {fmt(s['cpu'], '.2f')} | "
              f"{fmt(s['steps'], 'd')} | {err:.4e} | {spread:.1e} | {fmt(s['busy'], '.2f')} |")
        out["ritter"] = rit
        P("")
        # equal-accuracy time ratio
        byc = {}
        for k, v in rit.items():
            byc.setdefault(v["cfg"], []).append(v)
        talus_cfgs = [c for c in byc if not c.startswith("geoclaw")]
        ratios = {}
        for gcfg_ in [c for c in ("geoclaw", "geoclaw_dry1e-3") if c in byc]:
            P(f"Equal-accuracy time ratio against {TALUS_LABEL[gcfg_]}: the Talus time at GeoClaw's L1 error "
              "(log-time against log-error, piecewise linear; * = extrapolated beyond Talus's errors), divided "
              "by GeoClaw's time (< 1: Talus faster). Wall and CPU time.")
            P("")
            P("| GeoClaw dx m | GeoClaw L1 | GeoClaw wall s | GeoClaw cpu s | " + " | ".join(
                f"Talus {c}: wall s at that L1 | wall ratio | cpu ratio" for c in talus_cfgs) + " |")
            P("|---|---|---|---|" + "---|---|---|" * len(talus_cfgs))
            for v in sorted(byc[gcfg_], key=lambda v: -v["dx"]):
                cells = []
                for c in talus_cfgs:
                    lst = byc[c]
                    t, ex = loglog_interp([w["err"] for w in lst], [w["wall"] for w in lst], v["err"])
                    tc, _ = loglog_interp([w["err"] for w in lst], [w["cpu"] for w in lst], v["err"])
                    star = "*" if ex else ""
                    ratios.setdefault(f"{c}_vs_{gcfg_}", []).append(dict(dx=v["dx"], wall=t / v["wall"],
                                                                         cpu=tc / v["cpu"], extrapolated=ex))
                    cells.append(f"{t:.2f}{star} | {t / v['wall']:.2f}{star} | {tc / v['cpu']:.2f}{star}")
                P(f"| {v['dx']:g} | {v['err']:.4e} | {v['wall']:.2f} | {v['cpu']:.2f} | " + " | ".join(cells) + " |")
            P("")
            if all(r["extrapolated"] for c in talus_cfgs for r in ratios[f"{c}_vs_{gcfg_}"]):
                P("(Every entry is extrapolated: GeoClaw's errors lie outside the range of Talus's, so "
                  "this table is not meaningful.)")
                P("")
        out["ritter_ratio"] = ratios

    for name, title in (("steep_plane.md", "Diagnostic: thin sheet on a steep plane"),
                        ("rough_slope.md", "Grid study: water sheet on a rough steep slope"),
                        ("roll_waves.md", "Roll waves on a steep plane: crest depths against the cell size")):
        path = os.path.join(work, name)
        if os.path.exists(path):
            P("## " + title)
            P("")
            lines.extend(open(path).read().rstrip("\n").split("\n"))
            P("")
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    open(os.path.join(work, "results.md"), "w").write(text)
    json.dump(out, open(os.path.join(work, "results.json"), "w"), indent=1, default=str)


def peers_io_records(work):
    path = os.path.join(work, "runs.jsonl")
    recs = []
    if os.path.exists(path):
        for ln in open(path):
            if ln.strip():
                recs.append(json.loads(ln))
    return recs


if __name__ == "__main__":
    main()
