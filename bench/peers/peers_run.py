#!/usr/bin/env python3
"""Runs Talus and GeoClaw jobs alternately, timing each process, and appends one JSON record per
run to WORK/runs.jsonl (a run already recorded there is not repeated, so an interrupted study
resumes where it stopped; delete runs.jsonl or pass --fresh to start over).

  peers_run.py kot    WORK [--reps N]              kot_dambreak at 5 m: Talus variants and GeoClaw
  peers_run.py grid   WORK [--reps N] [--levels]   grid study (10 m, 2.5 m; 5 m comes from `kot`)
  peers_run.py ritter WORK [--reps N] [--dx]       Ritter dam break

Environment: TALUS_BIN (the Talus executable; the entry script passes a snapshot copy),
GEOCLAW_EXE (xgeoclaw built by the entry script).
"""
import argparse
import glob
import json
import os
import resource
import shutil
import subprocess
import sys
import time

import peers_io

HERE = os.path.dirname(os.path.abspath(__file__))

# Talus configurations. "grid" is the one used in the grid study: Talus's default precision with
# the slope correction off, i.e. the classical shallow-water equations that GeoClaw solves.
TALUS_CONFIGS = {
    "float":          ["Precision=float"],
    "double":         ["Precision=double"],
    "float_sc0":      ["Precision=float", "Slope Correction=0"],
    "double_sc0":     ["Precision=double", "Slope Correction=0"],
    # the dimensionally split sweeps (per-direction CFL), at the Courant number 1/2 and at 0.9 (above
    # 1/2 positive by the draining time, kernels/flow/stage.cl); GeoClaw's desired Courant number is 0.9
    "float_sc0_split":       ["Precision=float", "Slope Correction=0", "Time Scheme=split"],
    "float_sc0_split_cfl09": ["Precision=float", "Slope Correction=0", "Time Scheme=split", "CFL=0.9"],
    "float_split_cfl09":     ["Precision=float", "Time Scheme=split", "CFL=0.9"],
    # the split sweeps as one MUSCL-Hancock stage each (kernels/flow/hancock.cl), at 0.9
    "float_sc0_hancock_cfl09": ["Precision=float", "Slope Correction=0", "Time Scheme=hancock", "CFL=0.9"],
    "float_hancock_cfl09":     ["Precision=float", "Time Scheme=hancock", "CFL=0.9"],
}
GRID_TALUS_CONFIG = os.environ.get("PEERS_GRID_TALUS_CONFIG", "float_sc0")


def load_records(work):
    path = os.path.join(work, "runs.jsonl")
    recs = []
    if os.path.exists(path):
        for ln in open(path):
            ln = ln.strip()
            if ln:
                recs.append(json.loads(ln))
    return recs


def append_record(work, rec):
    with open(os.path.join(work, "runs.jsonl"), "a") as f:
        f.write(json.dumps(rec) + "\n")


def talus_job(work, case, config, threads, runfile, extra_sets=()):
    return dict(code="talus", case=case, config=config, threads=threads, runfile=runfile,
                sets=list(TALUS_CONFIGS[config]) + list(extra_sets),
                key=f"talus/{case}/{config}/{threads}t")


def geoclaw_job(work, case, threads, dry1e3=False):
    """GeoClaw with dry_tolerance 1e-6 m (as Talus), or (dry1e3) with its default 1e-3 m."""
    config = "geoclaw_dry1e-3" if dry1e3 else "geoclaw"
    folder = case + ("__dry1e-3" if dry1e3 else "")
    return dict(code="geoclaw", case=case, config=config, threads=threads,
                data_dir=os.path.join(work, "geoclaw", folder), key=f"geoclaw/{case}/{config}/{threads}t")


def cpu_busy(interval=2.0):
    """Fraction of the machine's CPU time (all cores) spent busy over `interval` seconds."""
    def snap():
        v = [float(x) for x in open("/proc/stat").readline().split()[1:]]
        return sum(v), v[3] + (v[4] if len(v) > 4 else 0.0)
    t0, i0 = snap()
    time.sleep(interval)
    t1, i1 = snap()
    return 1.0 - (i1 - i0) / max(t1 - t0, 1e-9)


def _stat_jiffies():
    v = [float(x) for x in open("/proc/stat").readline().split()[1:]]
    return sum(v), v[3] + (v[4] if len(v) > 4 else 0.0)


CONTENDED = float(os.environ.get("PEERS_CONTENDED", "0.1"))


def wait_quiet():
    """Before a timed run, wait (up to PEERS_QUIET_WAIT s, default 300) until the other processes
    use less than PEERS_QUIET_BUSY (default 0.15) of the machine; returns (waited s, busy)."""
    max_wait = float(os.environ.get("PEERS_QUIET_WAIT", "300"))
    limit = float(os.environ.get("PEERS_QUIET_BUSY", "0.15"))
    t0 = time.time()
    while True:
        b = cpu_busy()
        if b < limit or time.time() - t0 >= max_wait:
            return round(time.time() - t0, 1), round(b, 3)
        time.sleep(3.0)


def _loadavg():
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return None


def run_job(work, job, rep):
    out = os.path.join(work, "runs", job["key"].replace("/", "__"), f"rep{rep}")
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    env = dict(os.environ)
    waited, busy = wait_quiet()
    rec = dict(key=job["key"], code=job["code"], case=job["case"], config=job["config"],
               threads=job["threads"], rep=rep, out_dir=out, load1_before=_loadavg(),
               busy_before=busy, waited_s=waited, started=time.strftime("%Y-%m-%dT%H:%M:%S"))
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    j0 = _stat_jiffies()
    if job["code"] == "talus":
        env.pop("POCL_MAX_PTHREAD_COUNT", None)
        if job["threads"] == 1:
            env["POCL_MAX_PTHREAD_COUNT"] = "1"  # PoCL 3.1 pthread device: 1 compute unit
        cmd = [os.environ["TALUS_BIN"], "run", job["runfile"], "--out", out, "--overwrite", "--quiet"]
        for s in job["sets"]:
            cmd += ["--set", s]
        log = open(os.path.join(out, "talus.log"), "w")
        t0 = time.perf_counter()
        p = subprocess.run(cmd, env=env, stdout=log, stderr=subprocess.STDOUT)
        wall = time.perf_counter() - t0
        log.close()
        rec.update(cmd=cmd, rc=p.returncode, wall_s=wall)
        if p.returncode == 0:
            s = peers_io.talus_summary(out)
            rec.update(steps=s["steps"], sim_s=s["simulated_s"], internal_wall_s=s["wall_time_s"],
                       final_m3=s["volume"]["final_m3"], outflow_m3=s["volume"]["outflow_m3"],
                       initial_m3=s["volume"]["initial_m3"], device=s.get("device"))
    else:
        for f in glob.glob(os.path.join(job["data_dir"], "*.data")):
            shutil.copy(f, out)
        env["OMP_NUM_THREADS"] = str(job["threads"])
        cmd = [os.environ["GEOCLAW_EXE"]]
        log = open(os.path.join(out, "run.log"), "w")
        t0 = time.perf_counter()
        p = subprocess.run(cmd, env=env, cwd=out, stdout=log, stderr=subprocess.STDOUT)
        wall = time.perf_counter() - t0
        log.close()
        rec.update(cmd=cmd, rc=p.returncode, wall_s=wall)
        if p.returncode == 0:
            st = peers_io.geoclaw_steps(os.path.join(out, "run.log"))
            meta = json.load(open(os.path.join(job["data_dir"], "case.json")))
            rec.update(steps=st["steps"], cfl_over_max=st["cfl_over_max"], max_cfl=st["max_cfl"],
                       sim_s=meta["tfinal"], internal_wall_s=peers_io.geoclaw_timing(out))
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    j1 = _stat_jiffies()
    rec["cpu_s"] = (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)
    # CPU that other processes used during the run, as a share of the machine (all cores)
    busy_s = ((j1[0] - j0[0]) - (j1[1] - j0[1])) / os.sysconf("SC_CLK_TCK")
    ncpu = os.cpu_count() or 1
    rec["others_share"] = round(max(0.0, busy_s - rec["cpu_s"]) / max(rec["wall_s"] * ncpu, 1e-9), 3)
    rec["load1_after"] = _loadavg()
    tag = "ok" if rec["rc"] == 0 else f"FAILED rc={rec['rc']}"
    print(f"  {job['key']:<44s} rep {rep:3d}: {rec['wall_s']:8.2f} s wall {rec['cpu_s']:8.2f} s cpu  "
          f"steps {rec.get('steps', '-')}  busy before {busy:.2f} (waited {waited:.0f} s), others during "
          f"{rec['others_share']:.2f}  {tag}", flush=True)
    append_record(work, rec)
    return rec


def warm_up(work, jobs):
    """One very short Talus run per precision, so PoCL's kernel cache is filled before timing."""
    seen = set()
    for j in jobs:
        if j["code"] != "talus":
            continue
        prec = [s for s in j["sets"] if s.startswith("Precision=")][0]
        if prec in seen:
            continue
        seen.add(prec)
        out = os.path.join(work, "runs", "warmup", prec.split("=")[1])
        os.makedirs(out, exist_ok=True)
        subprocess.run([os.environ["TALUS_BIN"], "run", j["runfile"], "--out", out, "--overwrite",
                        "--quiet", "--set", prec, "--set", "End Time=0.002"] +
                       sum([["--set", s] for s in j["sets"] if not s.startswith("Precision=")], []),
                       stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)


def run_rounds(work, talus_jobs, geoclaw_jobs, reps):
    """reps rounds; in each round the Talus jobs alternate with GeoClaw jobs (cycled), and every
    other round runs in reverse order so slow drifts of the machine do not favour either code."""
    done = {(r["key"], r["rep"]) for r in load_records(work) if r.get("rc") == 0}
    warm_up(work, talus_jobs)
    for rep in range(reps):
        seq = []
        gi = 0
        n = max(len(talus_jobs), len(geoclaw_jobs))
        for i in range(n):
            if i < len(talus_jobs):
                seq.append(talus_jobs[i])
            if geoclaw_jobs:
                seq.append(geoclaw_jobs[gi % len(geoclaw_jobs)])
                gi += 1
        if rep % 2 == 1:
            seq.reverse()
        counts = {}
        for job in seq:
            k = counts.get(job["key"], 0)
            counts[job["key"]] = k + 1
            rid = rep * 100 + k  # several runs of the same job in one round get distinct ids
            if (job["key"], rid) in done:
                continue
            rec = run_job(work, job, rid)
            # a run during which other processes took more than CONTENDED of the machine is
            # repeated (at most twice); the report uses the uncontended runs
            extra = 1
            while rec.get("others_share", 0) > CONTENDED and extra <= 2:
                rec = run_job(work, job, rid + 10 * extra)
                extra += 1


def cmd_kot(args):
    work = os.path.abspath(args.work)
    runfile = os.path.join(work, "grids", "r5", "talus.run")
    tj = []
    configs = ["float", "double", "float_sc0", "double_sc0", "float_sc0_split", "float_sc0_split_cfl09",
               "float_sc0_hancock_cfl09"]
    for c in configs:
        tj.append(talus_job(work, "kot_r5", c, 1, runfile))
    for c in ["float", "double"]:
        tj.append(talus_job(work, "kot_r5", c, 2, runfile))
    if GRID_TALUS_CONFIG not in configs:
        tj.append(talus_job(work, "kot_r5", GRID_TALUS_CONFIG, 1, runfile))
    gj = [geoclaw_job(work, "kot_r5", 1), geoclaw_job(work, "kot_r5", 2),
          geoclaw_job(work, "kot_r5", 1, dry1e3=True)]
    run_rounds(work, tj, gj, args.reps)


def cmd_grid(args):
    work = os.path.abspath(args.work)
    for res in args.levels.split(","):
        name = "r" + res.replace(".", "p")
        if name == "r5":
            continue  # the 5 m runs are the kot_dambreak runs
        runfile = os.path.join(work, "grids", name, "talus.run")
        print(f"grid {name}", flush=True)
        run_rounds(work, [talus_job(work, "kot_" + name, GRID_TALUS_CONFIG, 1, runfile)],
                   [geoclaw_job(work, "kot_" + name, 1)], args.reps)


def cmd_ritter(args):
    work = os.path.abspath(args.work)
    for dx in args.dx.split(","):
        name = "dx" + dx.replace(".", "p")
        runfile = os.path.join(work, "ritter", name, "talus.run")
        print(f"ritter {name}", flush=True)
        run_rounds(work, [talus_job(work, "ritter_" + name, "float", 1, runfile),
                          talus_job(work, "ritter_" + name, "double", 1, runfile),
                          talus_job(work, "ritter_" + name, "float_split_cfl09", 1, runfile),
                          talus_job(work, "ritter_" + name, "float_hancock_cfl09", 1, runfile)],
                   [geoclaw_job(work, "ritter_" + name, 1), geoclaw_job(work, "ritter_" + name, 1, dry1e3=True)],
                   args.reps)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    for name, fn in (("kot", cmd_kot), ("grid", cmd_grid), ("ritter", cmd_ritter)):
        p = sub.add_parser(name)
        p.add_argument("work")
        p.add_argument("--reps", type=int, default=3)
        p.add_argument("--fresh", action="store_true", help="forget earlier records of this work dir")
        if name == "grid":
            p.add_argument("--levels", default="10,5,2.5")
        if name == "ritter":
            p.add_argument("--dx", default="1,0.5,0.25")
        p.set_defaults(fn=fn)
    args = ap.parse_args()
    for var in ("TALUS_BIN", "GEOCLAW_EXE"):
        if not os.environ.get(var):
            sys.exit(f"{var} is not set")
    if args.fresh:
        path = os.path.join(os.path.abspath(args.work), "runs.jsonl")
        if os.path.exists(path):
            os.rename(path, path + ".old")
    args.fn(args)


if __name__ == "__main__":
    main()
