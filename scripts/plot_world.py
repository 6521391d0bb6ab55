#!/usr/bin/python3
"""Top view of a simulated substation and a route (from `swlio-sim --dump-world DIR`).

Usage: scripts/plot_world.py DIR OUT.png [TITLE]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLORS = {
    "wall": "#8c8c8c", "fence": "#4d4d4d", "pole": "#1f77b4", "transformer": "#d62728",
    "gantry": "#9467bd", "insulator": "#ff7f0e", "busbar": "#e377c2", "trench": "#bcbd22",
    "tree": "#2ca02c",
}


def draw_world(ax, path):
    seen = set()
    with open(path) as f:
        for row in csv.DictReader(f):
            cls = row["class"]
            color = COLORS.get(cls, "k")
            label = cls if cls not in seen else None
            seen.add(cls)
            x, y = float(row["x"]), float(row["y"])
            a, b, yaw = float(row["a"]), float(row["b"]), float(row["yaw"])
            if row["kind"] == "box":
                c, s = np.cos(yaw), np.sin(yaw)
                corner = (x - c * a + s * b, y - s * a - c * b)
                ax.add_patch(patches.Rectangle(corner, 2 * a, 2 * b, angle=np.degrees(yaw),
                                               color=color, label=label, alpha=0.8))
            elif row["kind"] == "cylinder":
                if abs(a - x) + abs(b - y) < 1e-6:  # vertical
                    ax.add_patch(patches.Circle((x, y), max(yaw, 0.3), color=color, label=label))
                else:
                    ax.plot([x, a], [y, b], color=color, lw=1, label=label)
            else:
                ax.add_patch(patches.Circle((x, y), a, color=color, alpha=0.4, label=label))


def main():
    folder, out = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    fig, ax = plt.subplots(figsize=(11, 8))
    draw_world(ax, f"{folder}/world.csv")
    route = np.genfromtxt(f"{folder}/route.csv", delimiter=",", names=True)
    sc = ax.scatter(route["x"], route["y"], c=route["speed_mps"], s=2, cmap="viridis", zorder=5)
    ax.plot(route["x"][0], route["y"][0], "k*", ms=14, zorder=6, label="start / end")
    fig.colorbar(sc, ax=ax, label="speed (m/s)")
    ax.set_aspect("equal")
    ax.set_xlabel("x east (m)")
    ax.set_ylabel("y north (m)")
    ax.set_title(title)
    ax.legend(loc="upper left", fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
