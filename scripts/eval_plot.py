#!/usr/bin/python3
"""Draws a swlio-eval result: top view of both trajectories with the error as colour, and the
error over time. Run by swlio-eval (--plot) with Debian's python3-numpy and python3-matplotlib.

Usage: eval_plot.py DATA.csv OUT.png TITLE [t|index] [ERROR_LABEL]
DATA.csv columns: t_s,ref_x,ref_y,ref_z,est_x,est_y,est_z,error (error empty where none).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, missing_values="",
                         filling_values=np.nan)
    return np.atleast_1d(data)


def top_view_axes(ref):
    """The two axes with the largest extent (x-y for TUM/robot data, x-z for KITTI cameras)."""
    extents = [np.ptp(ref[:, k]) for k in range(3)]
    a, b = sorted(np.argsort(extents)[-2:])
    return int(a), int(b)


def main(argv):
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    csv_path, png_path, title = argv[1], argv[2], argv[3]
    time_kind = argv[4] if len(argv) > 4 else "t"
    error_label = argv[5] if len(argv) > 5 else "error"
    d = load(csv_path)
    ref = np.column_stack([d["ref_x"], d["ref_y"], d["ref_z"]])
    est = np.column_stack([d["est_x"], d["est_y"], d["est_z"]])
    err = d["error"]
    has = np.isfinite(err)
    if not has.any():
        print("eval_plot.py: no error values in " + csv_path, file=sys.stderr)
        return 1
    a, b = top_view_axes(ref)
    names = "xyz"

    fig, (ax_top, ax_err) = plt.subplots(1, 2, figsize=(14, 6),
                                         gridspec_kw={"width_ratios": [1.1, 1]})
    fig.suptitle(title.replace("\n", " "))
    ax_top.plot(ref[:, a], ref[:, b], "--", color="0.5", lw=1, label="reference")
    ax_top.plot(est[:, a], est[:, b], "-", color="0.8", lw=0.8, label="estimate")
    sc = ax_top.scatter(est[has, a], est[has, b], c=err[has], cmap="jet", s=6, zorder=3)
    fig.colorbar(sc, ax=ax_top, label=error_label)
    ax_top.set_xlabel(names[a] + " (m)")
    ax_top.set_ylabel(names[b] + " (m)")
    ax_top.set_aspect("equal", adjustable="datalim")
    ax_top.legend(loc="best")
    ax_top.set_title("top view (" + names[a] + "-" + names[b] + ")")

    t = d["t_s"]
    if time_kind == "t":
        x = t[has] - t[0]
        ax_err.set_xlabel("t (s)")
    else:
        x = t[has]
        ax_err.set_xlabel("pose index")
    e = err[has]
    ax_err.plot(x, e, "-", color="tab:blue", lw=1, label="error")
    for value, name, style in ((np.sqrt(np.mean(e ** 2)), "rmse", "-"),
                               (np.mean(e), "mean", "--"), (np.median(e), "median", ":")):
        ax_err.axhline(value, color="tab:red", ls=style, lw=1, label=f"{name} {value:.4g}")
    ax_err.set_ylabel(error_label)
    ax_err.grid(True, alpha=0.3)
    ax_err.legend(loc="best")
    ax_err.set_title("error over time")

    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
