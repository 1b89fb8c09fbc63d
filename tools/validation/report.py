#!/usr/bin/env python3
"""Writes docs/validation.md from tools/validation/template.md (tools/validation/make_report.sh).

Every number in the report is read from files written by the run that make_report.sh just did:
the verification tests' CSVs and their GoogleTest JSON, and each scene's summary.json,
diagnostics.csv and run.resolved.run. Scene maps are rendered with `talus render`.

Template placeholders (one per line or inline):
  {{meta}}                         when, how and on what the report was made
  {{tests}}                        table of the verification tests run (status, time)
  {{test:Suite.Name}}              one test's status
  {{fig:NAME.png|caption}}         a figure from the image folder (a note when it is missing)
  {{table:FILE.csv[,FILE2.csv...]|col:Header:fmt|...}}
                                   a markdown table of the CSVs' columns (rows of several files
                                   with the same columns are concatenated); fmt is a Python format
                                   spec (".3e", ".2f", "d", "s"); NaN prints as an empty cell
  {{scenes}}                       one section per scene run (or skipped) by make_report.sh
  {{parts}}                        docs/validation_parts/*.md, in name order
"""
import argparse
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys

# The order of the scene sections (others follow in name order).
SCENE_ORDER = ["kot_dambreak", "kot_debrisflow", "block_slide", "paper_setup1_A", "paper_setup1_B", "paper_setup1_C",
               "paper_setup2_A", "paper_setup2_B", "paper_setup2_C", "paper_flume_c26", "paper_flume_c18"]


def read_csv(path):
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows or None


def read_diagnostics(path):
    """diagnostics.csv without a last row a killed run may have cut short."""
    rows = read_csv(path)
    while rows:
        try:
            float(rows[-1]["time_s"])
            float(rows[-1]["wall_s"])
            break
        except (TypeError, ValueError, KeyError):
            rows.pop()
    return rows or None


def fmt_value(text, spec):
    if spec in ("", "s"):
        return text
    try:
        v = float(text)
    except ValueError:
        return text
    if math.isnan(v):
        return ""
    if spec == "d":
        return str(int(round(v)))
    return format(v, spec)


class Report:
    def __init__(self, args):
        self.a = args
        self.repo = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
        self.doc_dir = os.path.dirname(os.path.abspath(args.out))
        self.tests = self.load_tests()

    # ---- paths ---------------------------------------------------------------------------------
    def rel(self, path):
        """A path relative to the report's folder, for links."""
        return os.path.relpath(os.path.abspath(path), self.doc_dir)

    def image(self, name):
        return os.path.join(self.a.images, name)

    # ---- tests ---------------------------------------------------------------------------------
    def load_tests(self):
        tests = {}
        for path in filter(None, self.a.gtest.split(",")):
            if not os.path.isfile(path):
                continue
            with open(path) as f:
                data = json.load(f)
            for suite in data.get("testsuites", []):
                for t in suite.get("testsuite", []):
                    name = "%s.%s" % (suite["name"], t["name"])
                    status = "passed"
                    if t.get("failures"):
                        status = "FAILED"
                    elif t.get("result") == "SKIPPED" or t.get("status") == "NOTRUN":
                        status = "skipped"
                    tests[name] = (status, t.get("time", ""))
        return tests

    def test_status(self, name):
        if name not in self.tests:
            return "`%s`: not run in this report" % name
        status, time = self.tests[name]
        return "`%s`: **%s** (%s)" % (name, status, time)

    def test_counts(self):
        if not self.tests:
            return "no results"
        counts = {}
        for status, _ in self.tests.values():
            counts[status] = counts.get(status, 0) + 1
        return ", ".join("%d %s" % (n, s) for s, n in sorted(counts.items()))

    def tests_table(self):
        if not self.tests:
            return "_No test results found (%s)._" % self.a.gtest
        lines = ["| test | result | time |", "|---|---|---|"]
        for name, (status, time) in sorted(self.tests.items()):
            lines.append("| `%s` | %s | %s |" % (name, status, time))
        return "\n".join(lines)

    # ---- figures and tables ----------------------------------------------------------------------
    def figure(self, arg):
        name, _, caption = arg.partition("|")
        path = self.image(name.strip())
        if not os.path.isfile(path):
            return "_(figure %s not produced: its test did not run or wrote no CSV)_" % name.strip()
        return "![%s](%s)" % (caption.strip() or name, self.rel(path))

    def table(self, arg):
        parts = arg.split("|")
        rows = []
        for name in parts[0].split(","):  # several CSVs with the same columns make one table
            rows += read_csv(os.path.join(self.a.csv, name.strip())) or []
        if not rows:
            return "_(table %s not produced: its test did not run)_" % parts[0].strip()
        cols = []
        for p in parts[1:]:
            bits = p.split(":")
            cols.append((bits[0].strip(), bits[1].strip() if len(bits) > 1 else bits[0].strip(),
                         bits[2].strip() if len(bits) > 2 else "s"))
        lines = ["| " + " | ".join(h for _, h, _ in cols) + " |", "|" + "---|" * len(cols)]
        for r in rows:
            lines.append("| " + " | ".join(fmt_value(r.get(c, ""), f) for c, _, f in cols) + " |")
        return "\n".join(lines)

    # ---- scenes ----------------------------------------------------------------------------------
    def scene_names(self):
        names = [os.path.basename(os.path.dirname(p)) for p in glob.glob(os.path.join(self.a.scenes, "*", "status.txt"))]
        order = {n: i for i, n in enumerate(SCENE_ORDER)}
        return sorted(names, key=lambda n: (order.get(n, len(order)), n))

    @staticmethod
    def key_values(path):
        out = {}
        if os.path.isfile(path):
            with open(path) as f:
                for line in f:
                    k, sep, v = line.strip().partition("=")
                    if sep and not k.startswith("#"):
                        out.setdefault(k.strip(), v.strip())
        return out

    def percentile_range(self, tif):
        """The 99th percentile of the positive values (so one deep cell does not wash out the ramp),
        or None when GDAL's Python bindings are not there."""
        try:
            from osgeo import gdal
            import numpy as np
        except ImportError:
            return None
        ds = gdal.Open(tif)
        band = ds.GetRasterBand(1)
        v = band.ReadAsArray().astype(float)
        nd = band.GetNoDataValue()
        if nd is not None:
            v = v[v != nd]
        v = v[np.isfinite(v) & (v > 0)]
        if v.size == 0:
            return None
        hi = float(np.percentile(v, 99))
        return hi if hi > 0 else None

    def render(self, tif, png, dem, label, ramp, extra=()):
        cmd = [self.a.talus, "render", tif, "-o", png, "--ramp", ramp, "--label", label]
        if dem and os.path.isfile(dem):
            cmd += ["--hillshade", dem]
        cmd += list(extra)
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return None, (r.stderr.strip() or r.stdout.strip())
        return png, None

    def scene_maps(self, name, out_dir, dem, cut_time):
        """Renders up to three maps of the scene; returns markdown lines."""
        maps = []
        have = lambda m: os.path.isfile(os.path.join(out_dir, m + ".tif"))  # noqa: E731
        peak = next((m for m in ("hsmax", "hfmax") if have(m)), None)
        deposit = next((m for m in ("hcfinal", "hsfinal", "hffinal") if have(m)), None)
        if peak:
            maps.append((peak, "%s [m], maximum" % peak, "depth", []))
        if deposit:
            maps.append((deposit, "%s [m], end time" % deposit, "depth", []))
        if have("cfracfinal"):
            maps.append(("cfracfinal", "cfracfinal c/c0, end time", "cohesion",
                         ["--range", "0", "1", "--threshold", "-0.5"]))
        if not maps:
            # A run cut by its wall-time budget has no final maps: show the last series map.
            index = read_csv(os.path.join(out_dir, "series", "index.csv"))
            if index:
                last = index[-1]
                t = last.get("time_s", "?")
                for v in last.values():
                    base = os.path.splitext(os.path.basename(v or ""))[0]
                    if (base.startswith("hs_") or base.startswith("hf_")) and have(os.path.join("series", base)):
                        maps.append((os.path.join("series", base), "%s [m], last report t = %s s" % (base[:2], t),
                                     "depth", []))
        lines = []
        if not any(have(m) for m in ("hsmax", "hfmax", "hcfinal", "cfracfinal")):
            # Without final maps (a cut run): keep only series maps with material on the grid, and
            # draw the particles of the last report (hybrid mode).
            maps = [m for m in maps if self.percentile_range(os.path.join(out_dir, m[0] + ".tif"))]
            fig = self.particle_figure(name, out_dir)
            if fig:
                lines.append(fig)
        for m, label, ramp, extra in maps:
            tif = os.path.join(out_dir, m + ".tif")
            png = self.image("scene_%s_%s.png" % (name, os.path.basename(m)))
            if ramp == "depth" and "--range" not in extra:
                hi = self.percentile_range(tif)
                if hi:
                    extra = extra + ["--range", "0", "%.4g" % hi]
                    label += ", ramp to the 99th pct"
            ok, err = self.render(tif, png, dem, "%s: %s" % (name, label), ramp, extra)
            if ok:
                lines.append("![%s %s](%s)" % (name, m, self.rel(ok)))
            else:
                lines.append("_(map %s not rendered: %s)_" % (m, err))
        return lines

    def particle_figure(self, name, out_dir):
        """The particles of the last report (particles/particles_NNNN.gpkg), coloured by their
        cohesion fraction; markdown, or None without particle layers or GDAL's Python bindings."""
        files = sorted(glob.glob(os.path.join(out_dir, "particles", "particles_*.gpkg")))
        index = read_csv(os.path.join(out_dir, "series", "index.csv")) or []
        if not files:
            return None
        try:
            from osgeo import ogr
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            return None
        path = files[-1]
        number = int(re.findall(r"(\d+)", os.path.basename(path))[-1])
        t = next((r["time_s"] for r in index if int(r["index"]) == number), "?")
        ds = ogr.Open(path)
        if ds is None:
            return None
        layer = ds.GetLayer(0)
        xs, ys, cs = [], [], []
        for f in layer:
            g = f.GetGeometryRef()
            if g is None:
                continue
            xs.append(g.GetX())
            ys.append(g.GetY())
            c = f.GetField("cohesion_fraction")
            cs.append(c if c is not None else float("nan"))
        if not xs:
            return None
        # Over the DEM's hillshade, in metres from the DEM's lower-left corner.
        x0 = y0 = 0.0
        dem_path = self.key_values(os.path.join(out_dir, "run.resolved.run")).get("DEM", "")
        fig, ax = plt.subplots(figsize=(7, 3.2))
        try:
            from osgeo import gdal
            from matplotlib.colors import LightSource
            dem = gdal.Open(dem_path)
            gt = dem.GetGeoTransform()
            z = dem.GetRasterBand(1).ReadAsArray().astype(float)
            nd = dem.GetRasterBand(1).GetNoDataValue()
            if nd is not None:
                z[z == nd] = float("nan")
            x0, y0 = gt[0], gt[3] + z.shape[0] * gt[5]
            shade = LightSource(azdeg=315, altdeg=45).hillshade(z, dx=gt[1], dy=-gt[5])
            ax.imshow(shade, cmap="gray", vmin=-0.3, vmax=1.2,
                      extent=(0, z.shape[1] * gt[1], 0, z.shape[0] * -gt[5]))
        except Exception:  # noqa: BLE001 - the particles alone still make the figure
            x0, y0 = min(xs), min(ys)
        xs = [x - x0 for x in xs]
        ys = [y - y0 for y in ys]
        sc = ax.scatter(xs, ys, c=cs, s=2, vmin=0, vmax=1, cmap="RdYlGn")
        fig.colorbar(sc, ax=ax, label="c/c0")
        ax.set_aspect("equal")
        ax.set_title("%s: %d particles at the last report, t = %s s" % (name, len(xs), t), fontsize=9)
        ax.set_xlabel("x [m] from the DEM's corner")
        ax.set_ylabel("y [m]")
        png = self.image("scene_%s_particles.png" % name)
        fig.tight_layout()
        fig.savefig(png, dpi=80)
        plt.close(fig)
        return "![%s particles](%s)" % (name, self.rel(png))

    def scene_section(self, name):
        out_dir = os.path.join(self.a.scenes, name)
        st = self.key_values(os.path.join(out_dir, "status.txt"))
        lines = ["### %s" % name, ""]
        readme = os.path.join(self.repo, "data", name, "README.md")
        run_file = st.get("run_file", "")
        src = "[%s](%s)" % (os.path.relpath(run_file, self.repo), self.rel(run_file)) if run_file else "?"
        if os.path.isfile(readme):
            src += ", described in [data/%s/README.md](%s)" % (name, self.rel(readme))
        lines.append("Run file: %s." % src)
        lines.append("")
        status = st.get("status", "?")
        if status == "skipped":
            lines.append("**Not run** in this report: %s." % st.get("reason", "quick mode"))
            return lines + [""]
        resolved = self.key_values(os.path.join(out_dir, "run.resolved.run"))
        summary = {}
        if os.path.isfile(os.path.join(out_dir, "summary.json")):
            with open(os.path.join(out_dir, "summary.json")) as f:
                summary = json.load(f)
        diag = read_diagnostics(os.path.join(out_dir, "diagnostics.csv"))
        end_min = resolved.get("End Time", "")
        start_min = resolved.get("Start Time", "0")
        end_s = (float(end_min) - float(start_min or 0)) * 60 if end_min else float("nan")
        reached = float(diag[-1]["time_s"]) if diag else 0.0
        wall = st.get("wall_s", "?")
        if status == "completed":
            verdict = "**ran to its end time** (%.4g s simulated) in %s s of wall time" % (reached, wall)
        elif status == "cut":
            verdict = ("**cut** by its wall-time budget of %s s at t = %.4g s of %.4g s simulated (%.1f %%)" %
                       (st.get("budget_s", "?"), reached, end_s, 100 * reached / end_s if end_s > 0 else 0))
        else:
            verdict = "**failed** (exit status %s) at t = %.4g s: `%s`" % (
                st.get("exit", "?"), reached, st.get("message") or "see out/validation/scenes/%s/talus.log" % name)
        lines.append("Result: %s." % verdict)
        lines.append("")
        rows = []
        if summary:
            g = summary.get("grid", {})
            rows.append(("grid", "%s × %s cells of %.4g m" % (g.get("nx"), g.get("ny"), g.get("dx", float("nan")))))
            rows.append(("device, precision", "%s, %s" % (summary.get("device"), summary.get("precision"))))
            rows.append(("steps, wall time", "%s steps in %.1f s (%.3g cell-updates/s)" %
                         (summary.get("steps"), summary.get("wall_time_s", float("nan")),
                          summary.get("cell_updates_per_s", float("nan")))))
            vol = summary.get("volume", {})
            if vol:
                rows.append(("volume (grid)", "initial %.6g m³, final %.6g m³, outflow %.6g m³" %
                             (vol.get("initial_m3", float("nan")), vol.get("final_m3", float("nan")),
                              vol.get("outflow_m3", float("nan")))))
                rows.append(("volume balance error", "%.2e" % vol.get("balance_error", float("nan"))))
        if diag:
            first, last = diag[0], diag[-1]
            if not summary:
                rows.append(("steps, wall time", "%s steps in %s s (from diagnostics.csv)" % (last["step"], last["wall_s"])))
                rows.append(("volume balance error (last step)", "%s" % last.get("balance_error", "")))
            if float(last.get("solid_volume_m3", 0) or 0) > 0 or float(first.get("solid_volume_m3", 0) or 0) > 0:
                rows.append(("solids / fluid on the grid", "first step %.5g / %.5g m³, last step %.5g / %.5g m³" % (
                    float(first["solid_volume_m3"]), float(first["fluid_volume_m3"]), float(last["solid_volume_m3"]),
                    float(last["fluid_volume_m3"]))))
            if float(first.get("particles", 0) or 0) > 0:
                m0 = float(first["particle_mass_kg"])
                out = sum(float(r.get("particle_outflow_kg", 0) or 0) for r in diag)
                m1 = float(last["particle_mass_kg"])
                rows.append(("particles", "%d at the first step, %d at the last" % (int(float(first["particles"])),
                                                                                  int(float(last["particles"])))))
                rows.append(("particle mass change", "(M + outflow − M₀)/M₀ = %.2e, outflow %.4g kg (water released "
                             "from broken bonds to the grid leaves the particles)" %
                             ((m1 + out - m0) / m0 if m0 else float("nan"), out)))
        if rows:
            lines += ["| quantity | value |", "|---|---|"] + ["| %s | %s |" % r for r in rows] + [""]
        dem = resolved.get("DEM", "")
        lines += self.scene_maps(name, out_dir, dem, reached)
        return lines + [""]

    def scenes(self):
        names = self.scene_names()
        if not names:
            return "_No scene was run._"
        out = []
        summary = ["| scene | result | simulated | wall time [s] |", "|---|---|---|---|"]
        for n in names:
            st = self.key_values(os.path.join(self.a.scenes, n, "status.txt"))
            diag = read_diagnostics(os.path.join(self.a.scenes, n, "diagnostics.csv"))
            reached = "%.4g s" % float(diag[-1]["time_s"]) if diag else "–"
            summary.append("| %s | %s | %s | %s |" % (n, st.get("status", "?"), reached, st.get("wall_s", "–")))
        out.append("\n".join(summary))
        out.append("")
        for n in names:
            out.append("\n".join(self.scene_section(n)))
        return "\n".join(out)

    # ---- the rest --------------------------------------------------------------------------------
    def parts(self):
        files = sorted(glob.glob(os.path.join(self.a.parts, "*.md")))
        if not files:
            return "_No fragments in %s._" % self.rel(self.a.parts)
        chunks = []
        for f in files:
            with open(f) as fh:
                chunks.append("<!-- from %s -->\n%s" % (self.rel(f), fh.read().rstrip()))
        return "\n\n".join(chunks)

    def meta(self):
        def run(cmd):
            try:
                return subprocess.run(cmd, capture_output=True, text=True, cwd=self.repo).stdout.strip()
            except OSError:
                return ""
        commit = run(["git", "rev-parse", "--short", "HEAD"])
        dirty = " (with uncommitted changes)" if run(["git", "status", "--porcelain"]) else ""
        devices = run([self.a.talus, "devices"]).splitlines()
        return "\n".join([
            "- generated %s by `bash tools/validation/make_report.sh%s` (%s mode)" % (
                self.a.date, " --quick" if self.a.mode == "quick" else "", self.a.mode),
            "- source: commit %s%s" % (commit or "?", dirty),
            "- device: %s" % (devices[0] if devices else "?"),
            "- verification tests: %s; scenes: see [Scenes](#scenes)" % self.test_counts(),
        ])

    def expand(self, text):
        def sub(m):
            key, _, arg = m.group(1).partition(":")
            if key == "meta":
                return self.meta()
            if key == "tests":
                return self.tests_table()
            if key == "test":
                return self.test_status(arg.strip())
            if key == "fig":
                return self.figure(arg)
            if key == "table":
                return self.table(arg)
            if key == "scenes":
                return self.scenes()
            if key == "parts":
                return self.parts()
            return m.group(0)
        return re.sub(r"\{\{(.*?)\}\}", sub, text)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--template", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--csv", required=True)
    p.add_argument("--scenes", required=True)
    p.add_argument("--images", required=True)
    p.add_argument("--parts", required=True)
    p.add_argument("--gtest", default="", help="GoogleTest JSON result files, comma-separated")
    p.add_argument("--talus", required=True)
    p.add_argument("--mode", default="full")
    p.add_argument("--date", default="")
    a = p.parse_args()
    with open(a.template) as f:
        text = f.read()
    r = Report(a)
    out = r.expand(text)
    with open(a.out, "w") as f:
        f.write(out)
    print("report.py: wrote", a.out)


if __name__ == "__main__":
    sys.exit(main())
