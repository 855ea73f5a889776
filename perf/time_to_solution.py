#!/usr/bin/env python3
"""Time to a validated answer: wall time of each study run to its steady result, and whether
that result is within a tolerance (default 0.5%) of the reference at every station.

    perf/time_to_solution.py RUNS_DIR [--only GLOB ...] [--tol 0.005] [--markdown]

RUNS_DIR is a study's runs directory (`adrsph study cases/paper_study.toml --out RUNS_DIR`):
one directory per run (run.json, stations.csv) and RUNS_DIR/reference/pe<Pe>/stations.csv.
The default selection is issue 10's: the fine modern run at Pe = 1000 and the mid runs of every
Pe. The runs of cases/paper_study.toml are cold starts stopped by the steady criterion of
docs/steady-state.md, so the figure is what a user pays for a result a cold start confirms.
The wall time is that of the run alone (the reference and compare are not counted); a run
continued from checkpoints adds the wall time of every part (run.json `restarts` says how many).
"""
import argparse
import csv
import fnmatch
import json
import math
import sys
from pathlib import Path

DEFAULT_ONLY = ["paper-modern-pe1000-dx0.125", "paper-*-dx0.25"]


def stations(path):
    with open(path, newline="") as f:
        return {float(r["x_mm"]): float(r["C_mean"]) for r in csv.DictReader(f)}


def reference_key(pe):
    return "pe%d" % round(pe)


def row(run_dir, runs_dir, tol):
    info = json.loads((run_dir / "run.json").read_text())
    ref_file = runs_dir / "reference" / reference_key(info["Pe"]) / "stations.csv"
    run_st, ref_st = stations(run_dir / "stations.csv"), stations(ref_file)
    errors = {x: abs(run_st[x] - ref_st[x]) / ref_st[x] for x in sorted(ref_st) if x in run_st}
    worst = max(errors.values()) if errors else math.nan
    load = info.get("load_average") or {}
    rss = info.get("peak_rss_bytes") or 0
    return {
        "run": run_dir.name,
        "status": info.get("status", "?"),
        "wall_min": info["wall_seconds"] / 60.0,
        "threads": info.get("threads"),
        "steps": info["steps"],
        "mps": info["particle_steps_per_second"] / 1e6,
        "t_stop": info.get("t_steady") if info.get("steady") else info.get("t_reached"),
        "steady": bool(info.get("steady")),
        "errors": errors,
        "worst": worst,
        "ok": info.get("status") == "ok" and bool(info.get("steady")) and worst <= tol,
        "load": "%.1f/%.1f" % (load["start"], load["end"]) if load else "-",
        "rss_b_per_particle": rss / info["particles"] if rss else math.nan,
        "restarts": info.get("restarts", 0),
    }


def render(rows, tol, markdown):
    head = ["run", "wall [min]", "threads", "steps", "M particle-steps/s", "stopped at t [s]",
            "errors x = 25/50/100", "within %.2g%%" % (100 * tol), "load start/end",
            "peak RSS [B/particle]", "restarts"]
    lines = []
    for r in rows:
        errs = "/".join("%.3f%%" % (100 * e) for e in r["errors"].values())
        lines.append([r["run"], "%.1f" % r["wall_min"], str(r["threads"]), str(r["steps"]),
                      "%.2f" % r["mps"], "%.2f%s" % (r["t_stop"], "" if r["steady"] else " (not steady)"),
                      errs, "yes" if r["ok"] else "no", r["load"],
                      "%.0f" % r["rss_b_per_particle"], str(r["restarts"])])
    if markdown:
        out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        out += ["| " + " | ".join(l) + " |" for l in lines]
    else:
        widths = [max(len(h), *(len(l[i]) for l in lines)) if lines else len(h)
                  for i, h in enumerate(head)]
        out = ["  ".join(h.ljust(w) for h, w in zip(head, widths))]
        out += ["  ".join(c.ljust(w) for c, w in zip(l, widths)) for l in lines]
    return "\n".join(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs_dir", type=Path)
    ap.add_argument("--only", action="append", help="run-name glob (repeatable, comma-separated)")
    ap.add_argument("--tol", type=float, default=0.005, help="station error bound (0.005 = 0.5%%)")
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args(argv)
    if not a.runs_dir.is_dir():
        print("time_to_solution: %s is not a directory" % a.runs_dir, file=sys.stderr)
        return 2
    patterns = [p for o in (a.only or DEFAULT_ONLY) for p in o.split(",") if p]
    rows, missing = [], []
    for pattern in patterns:
        matched = sorted(d for d in a.runs_dir.iterdir()
                         if d.is_dir() and fnmatch.fnmatch(d.name, pattern))
        done = [d for d in matched if (d / "run.json").is_file() and (d / "stations.csv").is_file()]
        if not done:
            missing.append(pattern)
        rows += [row(d, a.runs_dir, a.tol) for d in done if d.name not in {r["run"] for r in rows}]
    print(render(rows, a.tol, a.markdown))
    for p in missing:
        print("not done yet: %s" % p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
