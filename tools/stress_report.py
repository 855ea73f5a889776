#!/usr/bin/env python3
"""The stability map of an `adrsph stress` study: where each scheme survives.

Usage: stress_report.py RUNS_DIR REPORT_DIR     (adrsph stress runs it at the end)
       stress_report.py --self-test             (a synthetic study, reported and checked)

Reads RUNS_DIR/study.json, each run's run.json (status, and for a failed run its "failure":
which guard, when, where), stations.csv and the reference of its Pe, as study_report.py does.
Each run differs from the `default` run of its scheme in one case key (its axis). Writes to
REPORT_DIR:
  stability.csv          one row per run: axis, value, survived, failure kind / time / place,
                         outlet error against the reference and change against the default run
  map_<scheme>.png       one row per axis, one cell per value: green survived (shade: outlet
                         change against the default run), red failed (the guard and time)
  README.md              the table per scheme and the safe range of every axis, in numbers
"""

import csv
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_report as sr  # noqa: E402  (re-executes under /usr/bin/python3 if it must)

import numpy as np  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap  # noqa: E402

try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = None

# The axes a stress study varies, in the order the map shows them: case key -> (label, the
# value the case takes when the key is absent or 0, how the value reads).
AXES = {
    "time.dt_factor": ("time step / stable limit", 1.0, "{:g}x"),
    "particles.jitter": ("start jitter / dx", 0.0, "{:g}"),
    "fluid.c0_factor": ("c0 / u_max", 10.0, "{:g}"),
    "Pe": ("Peclet number", 1000.0, "{:g}"),
    "modern.delta": ("density diffusion delta", 0.1, "{:g}"),
    "modern.shift_eps": ("shifting coefficient", 0.5, "{:g}"),
    "fluid.background_pressure": ("background pressure / rho0 c0^2", 0.025, "{:g}"),
}
# Keys every run of a stress study shares (they are not axes).
COMMON = {"scheme", "species.D", "particles.dx", "time.t_end", "time.stop_when_steady",
          "time.average_window", "output.field_times"}
# A survived run whose outlet moved more than this from its default run is flagged.
FLAG_CHANGE = 0.01


def axis_of(run):
    """(case key, value) that set this run apart; ("", nan) for a default run."""
    for key, value in run.sets.items():
        if key in COMMON:
            continue
        try:
            return key, float(value)
        except ValueError:
            return key, math.nan
    if run.group != "default" and run.sets.get("species.D") is not None:
        return "Pe", run.pe
    return "", math.nan


def case_defaults(run):
    """The run's own case.toml values of the axes (what `default` used), else AXES."""
    out = {k: v[1] for k, v in AXES.items()}
    path = os.path.join(run.dir, "case.toml")
    if tomllib is None or not os.path.isfile(path):
        return out
    with open(path, "rb") as f:
        case = tomllib.load(f)
    for key in AXES:
        if key == "Pe":
            continue
        node = case
        for part in key.split("."):
            node = node.get(part) if isinstance(node, dict) else None
        if isinstance(node, (int, float)) and not isinstance(node, bool):
            out[key] = float(node) if not (key == "time.dt_factor" and node == 0) else 1.0
    out["Pe"] = run.pe
    return out


class Row:
    def __init__(self, run, key, value, default_run):
        self.run, self.key, self.value = run, key, value
        self.scheme = run.scheme or "?"
        info = run.info or {}
        fail = info.get("failure") or {}
        self.state = run.state  # done / failed / not run
        self.kind = fail.get("kind") or ("" if run.state != sr.FAILED else "failed")
        self.t_fail = sr.num(fail.get("t"))
        self.x_fail, self.y_fail = sr.num(fail.get("x")), sr.num(fail.get("y"))
        self.fail_value = sr.num(fail.get("value"))
        self.outlet_err = run.outlet_err if run.done else math.nan
        # Signed relative change of the section averages against the default run of the scheme.
        # (Not across Peclet numbers: another Pe is another steady answer; its error against
        # its own reference is what the map shows there.)
        other_physics = key == "Pe"
        self.change = math.nan if other_physics else self.change_at(run, default_run, 100.0)
        self.change25 = math.nan if other_physics else self.change_at(run, default_run, 25.0)
        self.wall = run.wall
        self.steps = run.steps
        self.dt = sr.num((info.get("dt") or {}).get("chosen"))

    @staticmethod
    def change_at(run, default_run, x):
        c = run.station_c(x)
        c0 = default_run.station_c(x) if default_run else math.nan
        return (c - c0) / c0 if run.done and math.isfinite(c0) and c0 > 0 else math.nan

    @property
    def survived(self):
        return self.state == sr.DONE

    def short(self):
        if self.state == sr.NOT_RUN:
            return "not run"
        if not self.survived:
            t = f" t={self.t_fail:.3g}s" if math.isfinite(self.t_fail) else ""
            return f"{self.kind}{t}"
        if not self.key or self.key == "Pe":
            return f"error {sr.pct(self.outlet_err)}"
        return f"{signed_pct(self.change)} vs default"


def signed_pct(v):
    return "n/a" if not math.isfinite(v) else ("+" if v >= 0 else "-") + sr.pct(abs(v))


def collect(runs):
    defaults = {r.scheme: r for r in runs if r.group == "default"}
    rows = []
    for r in runs:
        key, value = axis_of(r)
        rows.append(Row(r, key, value, defaults.get(r.scheme)))
    return rows, defaults


def write_csv(rows, path):
    header = ["run", "scheme", "axis", "value", "survived", "failure", "t_fail_s", "x_fail_mm",
              "y_fail_mm", "failure_value", "outlet_error", "outlet_change_vs_default",
              "x25_change_vs_default", "dt_s", "steps", "wall_s"]
    out = []
    for w in rows:
        out.append([w.run.name, w.scheme, w.key or "default", sr.fnum(w.value, "{:g}"),
                    {sr.DONE: "yes", sr.FAILED: "no"}.get(w.state, "not run"), w.kind,
                    sr.fnum(w.t_fail), sr.fnum(w.x_fail), sr.fnum(w.y_fail),
                    sr.fnum(w.fail_value), sr.fnum(w.outlet_err), sr.fnum(w.change),
                    sr.fnum(w.change25), sr.fnum(w.dt), sr.fnum(w.steps, "{:.0f}"), sr.fnum(w.wall, "{:.1f}")])
    sr.write_csv(path, header, out)


def axis_cells(rows, scheme, key, default_row, default_value):
    """The cells of one axis for one scheme, sorted by value, the default run included."""
    cells = [(w.value, w) for w in rows if w.scheme == scheme and w.key == key]
    if not cells:
        return []
    if default_row is not None and all(v != default_value for v, _ in cells):
        cells.append((default_value, default_row))
    return sorted(cells, key=lambda vw: vw[0])


def safe_range(cells, default_value):
    """The contiguous range of values around the default in which every run survived, and
    the nearest failures on either side."""
    vals = [v for v, _ in cells]
    if default_value not in vals:
        return None
    i0 = vals.index(default_value)
    lo = hi = i0
    while lo > 0 and cells[lo - 1][1].survived:
        lo -= 1
    while hi + 1 < len(cells) and cells[hi + 1][1].survived:
        hi += 1
    below = cells[lo - 1] if lo > 0 else None
    above = cells[hi + 1] if hi + 1 < len(cells) else None
    return vals[lo], vals[hi], below, above


def plot_map(rows, scheme, defaults, report_dir):
    default_row = next((w for w in rows if w.scheme == scheme and not w.key), None)
    dvals = case_defaults(defaults[scheme]) if scheme in defaults else \
        {k: v[1] for k, v in AXES.items()}
    axes = [k for k in AXES if any(w.scheme == scheme and w.key == k for w in rows)]
    if not axes:
        return None
    width = max(len(axis_cells(rows, scheme, k, default_row, dvals[k])) for k in axes)
    fig, ax = plt.subplots(figsize=(1.6 * width + 3.2, 0.75 * len(axes) + 1.4))
    green = LinearSegmentedColormap.from_list("g", ["#2e9e44", "#c9e8a0"])
    for r, key in enumerate(axes):
        label, _, fmt = AXES[key]
        for c, (value, w) in enumerate(axis_cells(rows, scheme, key, default_row, dvals[key])):
            if w.state == sr.NOT_RUN:
                color = "#d0d0d0"
            elif w.survived:
                ch = abs(w.change) if math.isfinite(w.change) else 0.0
                color = green(min(ch / (2 * FLAG_CHANGE), 1.0))
            else:
                color = "#d9453b"
            ax.add_patch(plt.Rectangle((c, -r - 1), 1, 1, color=color, ec="white", lw=2))
            head = fmt.format(value) + (" (default)" if value == dvals[key] else "")
            ax.text(c + 0.5, -r - 0.35, head, ha="center", va="center", fontsize=8,
                    weight="bold" if value == dvals[key] else "normal")
            ax.text(c + 0.5, -r - 0.7, w.short(), ha="center", va="center", fontsize=7.5)
        ax.text(-0.1, -r - 0.5, label, ha="right", va="center", fontsize=9)
    ax.set_xlim(-3.2, width)
    ax.set_ylim(-len(axes), 0)
    ax.axis("off")
    ax.set_title(f"Stability map, {scheme} scheme (coarse reactor, t = 0..1 s): green survived "
                 f"(outlet section average against the default run; paler = further), "
                 f"red stopped by the guard named", fontsize=9)
    path = os.path.join(report_dir, f"map_{scheme}.png")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def fmt_value(key, v):
    return AXES[key][2].format(v) if key in AXES and math.isfinite(v) else sr.fnum(v, "{:g}")


def summary_lines(rows, scheme, defaults):
    default_row = next((w for w in rows if w.scheme == scheme and not w.key), None)
    dvals = case_defaults(defaults[scheme]) if scheme in defaults else \
        {k: v[1] for k, v in AXES.items()}
    lines = []
    for key in AXES:
        cells = axis_cells(rows, scheme, key, default_row, dvals[key])
        if not cells or any(w.state == sr.NOT_RUN for _, w in cells):
            if cells:
                lines.append(f"- {AXES[key][0]}: not all runs done")
            continue
        sr_ = safe_range(cells, dvals[key])
        if sr_ is None:
            continue
        lo, hi, below, above = sr_
        text = f"- {AXES[key][0]} (default {fmt_value(key, dvals[key])}): survived from " \
               f"{fmt_value(key, lo)} to {fmt_value(key, hi)} of the values tried"
        fails = []
        for side in (below, above):
            if side is not None:
                v, w = side
                fails.append(f"{fmt_value(key, v)} ({w.kind}"
                             + (f" at t = {w.t_fail:.3g} s" if math.isfinite(w.t_fail) else "")
                             + ")")
        text += "; failed at " + " and ".join(fails) if fails else \
            "; no failure in the range tried"
        moved = [(v, w) for v, w in cells if w.survived and math.isfinite(w.change)
                 and abs(w.change) > FLAG_CHANGE]
        if moved:
            text += "; survived but the outlet moved by more than " \
                    f"{sr.pct(FLAG_CHANGE, 0)} from the default run at " + ", ".join(
                        f"{fmt_value(key, v)} ({signed_pct(w.change)})" for v, w in moved)
        lines.append(text + ".")
    return lines


def write_report(runs_dir, report_dir):
    study, runs, _refs = sr.load_study(runs_dir)
    os.makedirs(report_dir, exist_ok=True)
    rows, defaults = collect(runs)
    write_csv(rows, os.path.join(report_dir, "stability.csv"))
    schemes = [s for s in ("conventional", "modern") if any(w.scheme == s for w in rows)]
    md = [f"# Stability map: {study.get('name', 'stress')}", "",
          "Generated by `tools/stress_report.py` from the runs of `adrsph stress` "
          "(`cases/stress_study.toml`). Every run is the coarse reactor (dx = 0.5 mm, Pe = 1000 "
          "unless its axis is Pe), started cold and run to t = 1 s, changed from the default "
          "run of its scheme in one case key. A run that survived ends at t = 1 s with every "
          "guard quiet (finite state, speed below 0.5 c0, density within 20% of rho0, C within "
          "its band, no particle through a wall); a run that failed was stopped by the named "
          "guard, which wrote the last good state and said what to change.", "",
          "The outlet error is the section average at x = 100 mm against the steady reference "
          "of the run's Pe, taken at t = 1 s. At that time the near-wall streamlines "
          "(u(y) < 100 mm/s) have not yet reached the outlet, so the default runs themselves are "
          + ", ".join(f"{sr.pct(defaults[s].outlet_err)} off ({s})" for s in
                      ("conventional", "modern") if s in defaults)
          + ": that is the start-up, not an error of the scheme. The map and the tables give "
          "each run's section averages *against the default run of its scheme* (signed, at "
          "x = 100 and 25 mm): the setting's own effect at the same moment of the start-up. "
          "Accuracy at steady state is in ../README.md.", "",
          "Wall times were taken while other runs shared the machine: compare the number of "
          "steps, not the seconds.", ""]
    for scheme in schemes:
        md += [f"## {scheme.capitalize()} scheme", ""]
        png = plot_map(rows, scheme, defaults, report_dir)
        if png:
            md += [f"![{scheme} map]({os.path.basename(png)})", ""]
        md += ["Safe ranges (contiguous, around the default, of the values tried):", ""]
        md += summary_lines(rows, scheme, defaults) + [""]
        table = []
        for w in rows:
            if w.scheme != scheme:
                continue
            table.append([w.run.name, w.key or "default", fmt_value(w.key, w.value),
                          "yes" if w.survived else ("not run" if w.state == sr.NOT_RUN else "no"),
                          w.kind or "",
                          sr.fnum(w.t_fail, "{:.3g}") if not w.survived else "",
                          f"({w.x_fail:.1f}, {w.y_fail:.2f})"
                          if math.isfinite(w.x_fail) and math.isfinite(w.y_fail) else "",
                          sr.pct(w.outlet_err), signed_pct(w.change), signed_pct(w.change25),
                          sr.fnum(w.dt, "{:.3g}"),
                          sr.fnum(w.wall, "{:.0f}")])
        md += [sr.md_table(["run", "axis", "value", "survived", "guard", "t fail [s]",
                             "where (x, y) [mm]", "outlet error", "outlet vs default",
                            "x = 25 vs default", "dt [s]", "wall [s]"], table), ""]
    md += ["Data: [stability.csv](stability.csv) (one row per run; `failure_value` is the "
           "quantity that tripped the guard: speed in mm/s, |rho/rho0 - 1|, the distance of C "
           "outside its band, or the number of particles lost).", ""]
    with open(os.path.join(report_dir, "README.md"), "w") as f:
        f.write("\n".join(md))
    return rows


# ----------------------------------------------------------------------------- self-test

def self_test():
    """A synthetic stress study: two schemes, a dt axis with a failure, a jitter axis."""
    import json
    with tempfile.TemporaryDirectory() as root:
        runs_dir, report = os.path.join(root, "runs"), os.path.join(root, "report")
        ref = os.path.join(runs_dir, "reference", "pe1000")
        os.makedirs(ref)
        with open(os.path.join(ref, "stations.csv"), "w") as f:
            f.write("x_mm,C_mean\n25,1.5\n50,1.1\n100,0.6\n")
        entries = []

        def run(name, group, scheme, sets, status, outlet=0.61, failure=None):
            d = os.path.join(runs_dir, name)
            os.makedirs(d)
            info = {"scheme": scheme, "flow": "wcsph", "Pe": 1000.0, "dx": 0.5,
                    "status": status, "message": "", "failure": failure,
                    "wall_seconds": 10.0, "steps": 100, "dt": {"chosen": 1e-4},
                    "stations": {"25": 1.5, "50": 1.1, "100": outlet}}
            with open(os.path.join(d, "run.json"), "w") as f:
                json.dump(info, f)
            with open(os.path.join(d, "case.toml"), "w") as f:
                f.write("[particles]\njitter = 0.0\n[time]\ndt_factor = 0.0\n")
            entries.append({"name": name, "group": group, "dir": name,
                            "reference": "reference/pe1000", "Pe": 1000.0, "status": status,
                            "sets": [f"scheme={scheme}", "species.D=10", "particles.dx=0.5"]
                            + sets})
        fail = {"kind": "density", "t": 0.02, "step": 40, "x": 91.0, "y": 0.2, "value": 0.21}
        for s in ("conventional", "modern"):
            run(f"default-{s}", "default", s, [], "ok")
            run(f"dt-{s}-2", "dt", s, ["time.dt_factor=2"], "ok", outlet=0.62)
            run(f"dt-{s}-4", "dt", s, ["time.dt_factor=4"], "ok" if s == "modern" else "failed",
                failure=None if s == "modern" else fail)
            run(f"dt-{s}-8", "dt", s, ["time.dt_factor=8"], "failed", failure=fail)
            run(f"jitter-{s}-0.3", "jitter", s, ["particles.jitter=0.3"], "ok")
        with open(os.path.join(runs_dir, "study.json"), "w") as f:
            json.dump({"name": "selftest", "runs": entries,
                       "references": [{"Pe": 1000.0, "dir": "reference/pe1000"}]}, f)
        rows = write_report(runs_dir, report)
        text = open(os.path.join(report, "README.md")).read()
        checks = [
            (len(rows) == 10, "ten rows"),
            (os.path.isfile(os.path.join(report, "map_conventional.png")), "conventional map"),
            (os.path.isfile(os.path.join(report, "map_modern.png")), "modern map"),
            ("survived from 1x to 2x of the values tried; failed at 4x (density at t = 0.02 s)"
             in text, "conventional dt range"),
            ("survived from 1x to 4x of the values tried; failed at 8x" in text,
             "modern dt range"),
            ("at 2x (+1.64%)" in text, "outlet change of 2x flagged"),
        ]
        with open(os.path.join(report, "stability.csv")) as f:
            table = list(csv.DictReader(f))
        dt4 = next(r for r in table if r["run"] == "dt-conventional-4")
        checks += [(dt4["survived"] == "no" and dt4["failure"] == "density"
                    and dt4["x_fail_mm"] == "91", "failure columns"),
                   (next(r for r in table if r["run"] == "default-modern")["axis"] == "default",
                    "default row")]
        bad = [what for ok, what in checks if not ok]
        for what in bad:
            print(f"stress_report self-test: FAILED: {what}")
        if bad:
            print(text)
            return 1
        print(f"stress_report self-test: {len(checks)} checks passed")
        return 0


def main():
    args = sys.argv[1:]
    if args == ["--self-test"]:
        sys.exit(self_test())
    if len(args) != 2 or args[0].startswith("-"):
        sys.exit(__doc__)
    if not os.path.isdir(args[0]):
        sys.exit(f"stress_report: {args[0]}: no such directory")
    rows = write_report(args[0], args[1])
    done = sum(1 for w in rows if w.state != sr.NOT_RUN)
    print(f"stress_report: {done} of {len(rows)} runs reported; wrote "
          f"{os.path.join(args[1], 'README.md')}")


if __name__ == "__main__":
    main()
