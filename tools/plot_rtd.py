#!/usr/bin/env python3
"""The measured normalised outlet response of a tracer-pulse run against the Taylor-Aris model.

Reads the CSV written by `adrsph rtd` (t_s,C_out,E_per_s,C_model,C_model_closed) and its
rtd.json (the feed's base and the model's area on the same samples), and draws
E_out = (C_out - base) / area against the model's (C_model - base) / model area (semi-infinite
medium) and the model on the channel's boundary conditions (C_model_closed, normalised by its
own area on the samples), with the measured outlet mean and the model's (feed mean + V/Q)
marked (docs/rtd.md). With `adrsph rtd --against`, also the transient finite-volume reference's
normalised response (C_reference - base) / its own area (rtd.json "reference").

usage: plot_rtd.py RTD.csv [--json RTD.json] [--out FILE.png] [--title TEXT]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = ["t_s", "C_out", "E_per_s", "C_model", "C_model_closed"]
OPTIONAL = ["C_reference"]  # filled by `adrsph rtd --against` only; absent in older files


def read_rtd(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no data rows")
    missing = [c for c in COLUMNS if c not in rows[0]]
    if missing:
        sys.exit(f"{path}: missing columns {missing}")
    # The model columns are empty where there is no model (species.D = 0).
    present = COLUMNS + [c for c in OPTIONAL if c in rows[0]]
    return {k: [float(r[k]) if r[k] else None for r in rows] for k in present}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--json", default=None, help="rtd.json (default: CSV name with .json)")
    ap.add_argument("--out", default=None, help="PNG file (default: CSV name with .png)")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    stem = args.csv.rsplit(".", 1)[0]
    data = read_rtd(args.csv)
    with open(args.json or stem + ".json") as f:
        info = json.load(f)
    out = args.out or stem + ".png"

    base = info["feed"]["base"]
    model_area = info["model"]["outlet_area"]
    fig, ax = plt.subplots(figsize=(7, 4.2), dpi=120)
    ax.plot(data["t_s"], data["E_per_s"], "-", label="run: (C_out - base) / area")
    if model_area:
        model = [None if c is None else (c - base) / model_area for c in data["C_model"]]
        ax.plot(data["t_s"], model, "--",
                label=f"Taylor-Aris, semi-infinite, Pe_L = {info['model']['Pe_L']:.3g}")
        t, closed = data["t_s"], [c - base for c in data["C_model_closed"]]
        area = sum(0.5 * (t[i] - t[i - 1]) * (closed[i] + closed[i - 1]) for i in range(1, len(t)))
        if area:
            ax.plot(t, [v / area for v in closed], "-.",
                    label="Taylor-Aris, channel's boundary conditions")
    reference = info.get("reference")
    c_ref = data.get("C_reference")
    if reference and c_ref and all(c is not None for c in c_ref):
        ax.plot(data["t_s"], [(c - base) / reference["outlet"]["area"] for c in c_ref], "-",
                color="k", lw=1.0, label="transient finite-volume reference")
    ax.axvline(info["outlet"]["mean"], color="C0", lw=0.8, ls=":", label="run: outlet mean")
    if info["feed"]["mean"] is not None and info["space_time"] is not None:
        ax.axvline(info["feed"]["mean"] + info["space_time"], color="C1", lw=0.8, ls=":",
                   label="feed mean + V/Q")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("normalised outlet response [1/s]")
    ax.set_xlim(min(data["t_s"]), max(data["t_s"]))
    ax.grid(True, alpha=0.3)
    ax.legend()
    if args.title:
        ax.set_title(args.title)
    fig.tight_layout()
    # Saved beside the target and renamed: a failed plot leaves no half-written PNG.
    tmp = out + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
