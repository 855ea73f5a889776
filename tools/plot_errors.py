#!/usr/bin/env python3
"""Relative error curves of a run against the reference, like the paper's figures 3-5.

Reads the CSV written by `adrsph compare` (x_mm,err_y0,err_y+2.5,err_y-2.5,err_mean) and
draws |C - C_ref| / C_ref against x on the three probe lines (and the section average),
log scale (docs/benchmark.md, section 4).

usage: plot_errors.py ERRORS.csv [--out FILE.png] [--title TEXT]
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = [
    ("err_y0", "y = 0", "-"),
    ("err_y+2.5", "y = +2.5 mm", "--"),
    ("err_y-2.5", "y = -2.5 mm", ":"),
    ("err_mean", "section average", "-."),
]


def read_errors(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no data rows")
    missing = [c for c, _, _ in COLUMNS + [("x_mm", "", "")] if c not in rows[0]]
    if missing:
        sys.exit(f"{path}: missing columns {missing}")
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out", default=None, help="PNG file (default: CSV name with .png)")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    data = read_errors(args.csv)
    out = args.out or args.csv.rsplit(".", 1)[0] + ".png"

    floor = 1e-7  # log scale: zeros drawn at the floor
    fig, ax = plt.subplots(figsize=(7, 4.2), dpi=120)
    for key, label, style in COLUMNS:
        ax.semilogy(data["x_mm"], [max(v, floor) for v in data[key]], style, label=label)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("relative error |C - C_ref| / C_ref")
    ax.set_xlim(0, max(data["x_mm"]))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    if args.title:
        ax.set_title(args.title)
    fig.tight_layout()
    fig.savefig(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
