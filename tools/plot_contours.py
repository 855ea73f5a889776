#!/usr/bin/env python3
"""Steady contour lines of C, SPH against the reference, like the paper's figure 2.

Reads the last frame of RUN_DIR/fields.h5 (groups /frame_NNNNNN with datasets x, y, c, kind;
kind 0 = fluid) and REF_DIR/reference.h5 (x (nx), y (ny), C (ny x nx)), interpolates the
scattered fluid particles to the reference grid (linear, Delaunay via matplotlib.tri) and
draws both sets of contour lines on one channel (docs/benchmark.md, section 4). Either input may be
omitted to draw the other alone.

usage: plot_contours.py [--run RUN_DIR] [--ref REF_DIR] [--out FILE.png] [--levels N]

The drawing is also a library: contour_figure() / draw_contours() (tools/study_report.py).
"""
import argparse
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402


def read_reference(ref_dir):
    path = os.path.join(ref_dir, "reference.h5")
    with h5py.File(path, "r") as f:
        return f["x"][:], f["y"][:], f["C"][:, :], dict(f.attrs)


def read_last_frame(run_dir):
    path = os.path.join(run_dir, "fields.h5")
    with h5py.File(path, "r") as f:
        frames = sorted(k for k in f.keys() if k.startswith("frame_"))
        if not frames:
            raise ValueError(f"{path}: no /frame_NNNNNN groups")
        g = f[frames[-1]]
        fluid = g["kind"][:] == 0
        t = g.attrs.get("time", float("nan"))
        return g["x"][:][fluid], g["y"][:][fluid], g["c"][:][fluid], t, frames[-1]


def sph_on_grid(xp, yp, cp, xg, yg):
    """Linear interpolation of scattered particle values on the grid (NaN outside the hull)."""
    tri = mtri.Triangulation(xp, yp)
    interp = mtri.LinearTriInterpolator(tri, cp)
    X, Y = np.meshgrid(xg, yg)
    return np.ma.filled(interp(X, Y).astype(float), np.nan)


def draw_contours(ax, run_dir=None, ref_dir=None, levels=10, stride=4, run_label=None):
    """Draws the reference (black) and the SPH (red, dashed) contour lines of C on `ax`.

    Either directory may be None. `run_label` names the SPH lines in the legend (default: the
    frame name). Returns (legend handles, reference attributes).
    """
    if ref_dir:
        xr, yr, cr, attrs = read_reference(ref_dir)
    else:
        xr = np.linspace(0.25, 99.75, 200)
        yr = np.linspace(-4.95, 4.95, 40)
        cr, attrs = None, {}
    xg, yg = xr[::stride], yr[:: max(1, stride // 2)]

    c_in = float(attrs.get("c_in", 2.0))
    level_values = np.linspace(0.0, c_in, levels + 2)[1:-1]
    handles = []
    if cr is not None:
        cs = ax.contour(xr, yr, cr, levels=level_values, colors="k", linewidths=1.0)
        ax.clabel(cs, fmt="%.2f", fontsize=7)
        handles.append(plt.Line2D([], [], color="k", label="reference (FV)"))
    if run_dir:
        xp, yp, cp, t, name = read_last_frame(run_dir)
        cg = sph_on_grid(xp, yp, cp, xg, yg)
        ax.contour(xg, yg, cg, levels=level_values, colors="tab:red", linewidths=1.0,
                   linestyles="--")
        handles.append(plt.Line2D([], [], color="tab:red", ls="--",
                                  label=f"SPH ({run_label or name}, t = {t:.3g} s)"))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("auto")
    return handles, attrs


def contour_figure(out, run_dir=None, ref_dir=None, levels=10, stride=4, run_label=None,
                   title=None):
    """Writes the contour plot (SPH against the reference) to the PNG `out`."""
    fig, ax = plt.subplots(figsize=(11, 3.2), dpi=130)
    try:
        handles, attrs = draw_contours(ax, run_dir, ref_dir, levels, stride, run_label)
        if title is None:
            title = "steady C contours"
            if "D" in attrs:
                title += f", D = {float(attrs['D']):g} mm^2/s"
        ax.set_title(title)
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8)
        fig.tight_layout()
        fig.savefig(out)
    finally:
        plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--run", help="run directory holding fields.h5")
    ap.add_argument("--ref", help="reference directory holding reference.h5")
    ap.add_argument("--out", default="contours.png")
    ap.add_argument("--levels", type=int, default=10, help="number of contour levels")
    ap.add_argument("--stride", type=int, default=4, help="reference grid subsampling")
    args = ap.parse_args()
    if not args.run and not args.ref:
        ap.error("give --run, --ref or both")
    try:
        contour_figure(args.out, args.run, args.ref, args.levels, args.stride)
    except (ValueError, OSError, KeyError) as e:
        sys.exit(str(e))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
