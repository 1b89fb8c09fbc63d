"""Readers for GeoClaw's output (frames, aux, fgmax, step log) and Talus's output folder, and a
runner for a prepared single-level GeoClaw case."""
import glob
import json
import os
import re
import shutil
import subprocess

import numpy as np

_HEADER_KEYS = ("grid_number", "AMR_level", "mx", "my", "xlow", "ylow", "dx", "dy")


def _frame_meta(run_dir, frame):
    """fort.tNNNN: time, num_eqn+1 (q columns written), num_grids, num_aux, num_dim, num_ghost, format."""
    lines = open(os.path.join(run_dir, "fort.t%04d" % frame)).read().split("\n")
    vals = [ln.split()[0] for ln in lines if ln.strip()]
    return dict(time=float(vals[0]), nq=int(vals[1]), ngrids=int(vals[2]), naux=int(vals[3]),
                ndim=int(vals[4]), nghost=int(vals[5]) if len(vals) > 5 else 2,
                fmt=vals[6] if len(vals) > 6 else "ascii")


def _patch_headers(qfile):
    """Headers of fort.qNNNN (binary formats: the file holds only headers)."""
    patches, cur = [], {}
    with open(qfile) as f:
        for ln in f:
            parts = ln.split()
            if len(parts) == 2 and parts[1] in _HEADER_KEYS:
                key = parts[1]
                cur[key] = float(parts[0].replace("D", "E").replace("d", "e"))
                if key == "dy":
                    patches.append({k: (int(v) if k in ("grid_number", "AMR_level", "mx", "my") else v)
                                    for k, v in cur.items()})
                    cur = {}
    return patches


def read_frame(run_dir, frame, nx, ny, dx):
    """Global arrays (rows from the top, as in the GeoTIFFs) of h, hu, hv, eta at output frame
    `frame` of a single-level GeoClaw run, and the frame time."""
    meta = _frame_meta(run_dir, frame)
    qfile = os.path.join(run_dir, "fort.q%04d" % frame)
    out = np.full((meta["nq"], ny, nx), np.nan)
    if meta["fmt"].startswith("binary"):
        dtype = np.float32 if meta["fmt"] == "binary32" else np.float64
        raw = np.fromfile(os.path.join(run_dir, "fort.b%04d" % frame), dtype=dtype)
        g = meta["nghost"]
        pos = 0
        for p in _patch_headers(qfile):
            mx, my = p["mx"], p["my"]
            n = meta["nq"] * (mx + 2 * g) * (my + 2 * g)
            a = raw[pos:pos + n].reshape(my + 2 * g, mx + 2 * g, meta["nq"])[g:g + my, g:g + mx, :]
            pos += n
            _place(out, a, p, ny, dx)
    else:
        with open(qfile) as f:
            text = f.read().split("\n")
        k = 0
        while k < len(text):
            parts = text[k].split()
            if len(parts) == 2 and parts[1] == "grid_number":
                p = {}
                for j in range(8):
                    v, key = text[k + j].split()[:2]
                    p[key] = float(v.replace("D", "E"))
                p["mx"], p["my"] = int(p["mx"]), int(p["my"])
                k += 8
                rows = []
                while len(rows) < p["mx"] * p["my"]:
                    s = text[k].split()
                    if s:
                        rows.append([float(v.replace("D", "E")) for v in s])
                    k += 1
                a = np.array(rows).reshape(p["my"], p["mx"], -1)
                _place(out, a, p, ny, dx)
            else:
                k += 1
    return out, meta["time"]


def read_aux(run_dir, frame, nx, ny, dx):
    """Topography B (aux 1) of a binary-format run on the global grid (rows from the top)."""
    meta = _frame_meta(run_dir, frame)
    g = meta["nghost"]
    dtype = np.float32 if meta["fmt"] == "binary32" else np.float64
    raw = np.fromfile(os.path.join(run_dir, "fort.a%04d" % frame), dtype=dtype)
    out = np.full((meta["naux"], ny, nx), np.nan)
    pos = 0
    for p in _patch_headers(os.path.join(run_dir, "fort.q%04d" % frame)):
        mx, my = p["mx"], p["my"]
        n = meta["naux"] * (mx + 2 * g) * (my + 2 * g)
        a = raw[pos:pos + n].reshape(my + 2 * g, mx + 2 * g, meta["naux"])[g:g + my, g:g + mx, :]
        pos += n
        _place(out, a, p, ny, dx)
    return out[0]


def _place(out, a, p, ny, dx):
    i0 = int(round(p["xlow"] / dx))
    j0 = int(round(p["ylow"] / dx))
    mx, my = a.shape[1], a.shape[0]
    # patch row j (from the bottom) -> global row from the top
    rows = ny - 1 - (j0 + np.arange(my))
    for m in range(min(out.shape[0], a.shape[2])):
        out[m, rows, i0:i0 + mx] = a[:, :, m]


def read_fgmax(run_dir, nx, ny, dx, fgno=1):
    """fgmaxNNNN.txt (num_fgmax_val = 1): max depth and B per cell, rows from the top."""
    d = np.loadtxt(os.path.join(run_dir, "fgmax%04d.txt" % fgno), ndmin=2)
    col = np.floor(d[:, 0] / dx).astype(int)
    row = ny - 1 - np.floor(d[:, 1] / dx).astype(int)
    hmax = np.full((ny, nx), np.nan)
    topo = np.full((ny, nx), np.nan)
    hmax[row, col] = d[:, 4]
    topo[row, col] = d[:, 3]
    return hmax, topo


_STEP_RE = re.compile(r"AMRCLAW: level\s+1\s+CFL\s*=\s*(\S+)\s+dt\s*=\s*(\S+)")


def geoclaw_steps(log_path):
    """Number of level-1 time steps and of steps over cfl_max, from the verbosity-1 log."""
    steps = over = 0
    cfl_max_seen = 0.0
    with open(log_path, errors="replace") as f:
        for ln in f:
            m = _STEP_RE.search(ln)
            if m:
                steps += 1
                try:
                    cfl_max_seen = max(cfl_max_seen, float(m.group(1)))
                except ValueError:
                    pass
            elif "larger than input cfl_max" in ln:
                over += 1
    return dict(steps=steps, cfl_over_max=over, max_cfl=cfl_max_seen)


def geoclaw_timing(run_dir):
    """Total wall time GeoClaw reports in timing.txt (None when absent)."""
    path = os.path.join(run_dir, "timing.txt")
    if not os.path.exists(path):
        return None
    for ln in open(path):
        if ln.strip().startswith("Total time:"):
            return float(ln.split()[2])
    return None


def talus_summary(out_dir):
    return json.load(open(os.path.join(out_dir, "summary.json")))


class MarkdownLog:
    """Report lines, printed as they come and kept for a markdown file: log(text), log.save(path)."""

    def __init__(self):
        self.lines = []

    def __call__(self, text):
        print(text, flush=True)
        self.lines.append(text)

    def save(self, path):
        with open(path, "w") as f:
            f.write("\n".join(self.lines) + "\n")


def run_geoclaw_case(case_dir, out_dir, nx, ny, dx, frame=1):
    """Runs GEOCLAW_EXE (one OpenMP thread) on the *.data files of case_dir in a fresh out_dir and
    returns read_frame's (q, t) of output frame `frame`."""
    shutil.rmtree(out_dir, ignore_errors=True)
    os.makedirs(out_dir)
    for f in glob.glob(os.path.join(case_dir, "*.data")):
        shutil.copy(f, out_dir)
    with open(os.path.join(out_dir, "run.log"), "w") as log:
        subprocess.run([os.environ["GEOCLAW_EXE"]], cwd=out_dir, check=True, stdout=log, stderr=subprocess.STDOUT,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    return read_frame(out_dir, frame, nx, ny, dx)


def run_talus(runfile, out_dir, sets=()):
    """Runs TALUS_BIN (PoCL with one compute unit) on `runfile` into out_dir with --set options."""
    cmd = [os.environ.get("TALUS_BIN", "talus"), "run", runfile, "--out", out_dir, "--overwrite", "--quiet"]
    for kv in sets:
        cmd += ["--set", kv]
    subprocess.run(cmd, check=True, env=dict(os.environ, POCL_MAX_PTHREAD_COUNT="1"))


def talus_variant(spec):
    """Run-file keys of a Talus variant named `limiter` or `limiter@scheme` (scheme: split or
    hancock, both at Courant number 0.9; e.g. mc@hancock), for the scripts' --limiters lists."""
    limiter, _, scheme = spec.partition("@")
    keys = ["Limiter=" + limiter]
    if scheme:
        keys += ["Time Scheme=" + scheme, "CFL=0.9"]
    return keys
