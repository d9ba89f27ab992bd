#!/usr/bin/python3
"""Top view of one flight: mapped obstacles, the flown path coloured by speed, and where each
planning mode's trajectory was committed.

Usage: plot_flight.py FLIGHT.json OUT.png   (FLIGHT.json from mmh-log-summary --export-flight)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

MODES = {1: ("FPM", "tab:cyan", "^"), 2: ("SOM", "tab:blue", "s"), 3: ("EAM", "tab:red", "D"),
         4: ("STOP", "black", "x")}


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    with open(sys.argv[1]) as fh:
        f = json.load(fh)
    res = f.get("resolution_m", 0.1)
    path = f["path"]
    fig, ax = plt.subplots(figsize=(13, 5))
    cells = f.get("occupied_xy", [])
    if cells:
        ax.scatter([(c[0] + 0.5) * res for c in cells], [(c[1] + 0.5) * res for c in cells],
                   s=2, marker="s", color="0.4", label="mapped obstacles", linewidths=0)
    if len(path) > 1:
        pts = [(p[1], p[2]) for p in path]
        segs = [[pts[i], pts[i + 1]] for i in range(len(pts) - 1)]
        speeds = [p[4] for p in path[:-1]]
        lc = LineCollection(segs, cmap="jet", linewidths=2.5)
        lc.set_array(speeds)
        lc.set_clim(0, max(3.0, max(speeds)))
        ax.add_collection(lc)
        fig.colorbar(lc, ax=ax, label="speed (m/s)", fraction=0.03, pad=0.01)
        ax.plot(*pts[0], "ko", ms=7, label="start")
    seen = set()
    for d in f.get("decisions", []):
        name, color, marker = MODES.get(d[3], ("?", "gray", "o"))
        ax.scatter(d[1], d[2], s=60, color=color, marker=marker, zorder=5,
                   edgecolors=None if marker == "x" else "white",
                   label=f"{name} committed" if name not in seen else None)
        seen.add(name)
    if "goal" in f:
        ax.plot(f["goal"][0], f["goal"][1], "k*", ms=14, label="goal")
    m = f.get("mission", {})
    title = "flight"
    if m:
        title = ("reached" if m["reached"] else "NOT reached") + \
            (" — COLLIDED" if m["collided"] else "") + \
            f" — {m['flight_time_s']:.2f} s, {m['distance_m']:.1f} m, energy {m['energy']:.0f} m²/s⁵"
    ax.set_title(title)
    xs = [p[1] for p in path] or [0]
    ys = [p[2] for p in path] or [0]
    ax.set_xlim(min(xs) - 2, max(xs) + 2)
    ax.set_ylim(min(ys) - 6, max(ys) + 6)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="upper left", fontsize=8, ncol=3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print("plot:", sys.argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main())
