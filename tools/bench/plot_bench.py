#!/usr/bin/python3
"""Plots of an mmh-bench run: the paper's Fig. 4 (top view of every method's path on one map
per density) and Fig. 5 (time, distance, energy and iterations over density).

Usage: plot_bench.py OUT_DIR   (reads OUT_DIR/results.json and OUT_DIR/paths/*.path.json)
"""
import glob
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

PAPER_MMH = {  # docs/benchmark.md: density -> (time, distance, energy, iterations)
    0.0: (16.52, 39.89, 15.56, 9.0),
    0.05: (17.04, 40.20, 43.93, 12.7),
    0.1: (17.89, 40.84, 80.91, 17.5),
    0.2: (18.62, 41.66, 136.43, 22.5),
}
COLORS = {"mmh": "tab:red", "ego": "tab:pink", "som": "tab:green",
          "mmh-no-lazy": "tab:blue", "mmh-no-awareness": "tab:orange"}


def mean_std(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    if not values:
        return float("nan"), 0.0
    m = sum(values) / len(values)
    s = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    return m, s


def top_views(out_dir, results):
    paths = {}
    for f in glob.glob(os.path.join(out_dir, "paths", "*.path.json")):
        with open(f) as fh:
            p = json.load(fh)
        paths[(p["method"], p["density"], p["map_index"], p["trial"])] = p
    densities = sorted({r["density"] for r in results})
    methods = list(dict.fromkeys(r["method"] for r in results))
    written = []
    for d in densities:
        fig, ax = plt.subplots(figsize=(12, 4.2))
        cylinders = None
        rings = None
        for m in methods:
            p = paths.get((m, d, 0, 0))
            if not p:
                continue
            cylinders = cylinders or p["cylinders"]
            rings = rings or p.get("rings")  # ego-forest: [x, y, horizontal semi-axis, yaw]
            xs = [s[1] for s in p["path"]]
            ys = [s[2] for s in p["path"]]
            label = m + ("" if p["success"] else " (failed)")
            ax.plot(xs, ys, color=COLORS.get(m, None), lw=1.6, label=label)
        for c in cylinders or []:
            ax.add_patch(Circle((c[0], c[1]), c[2], color="0.35", alpha=0.8, lw=0))
        for x, y, a, yaw in rings or []:
            # A vertical ring seen from above: a segment across its plane's horizontal axis.
            dx, dy = -a * math.sin(yaw), a * math.cos(yaw)
            ax.plot([x - dx, x + dx], [y - dy, y + dy], color="tab:brown", lw=2)
        r0 = next((r for r in results if r["density"] == d), None)
        if r0:
            ax.plot(*r0["start"][:2], "ko", ms=6)
            ax.plot(*r0["goal"][:2], "k*", ms=12)
        ax.set_aspect("equal")
        ax.set_xlim(-22, 22)
        ax.set_ylim(-7, 7)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        title = "own world" if d < 0 else f"{d:g} obs/m²"
        ax.set_title(f"Paths of every method on map 0, trial 0 — {title}")
        ax.legend(loc="upper right", fontsize=8)
        name = os.path.join(out_dir, "topview_own.png" if d < 0 else f"topview_d{d:g}.png")
        fig.tight_layout()
        fig.savefig(name, dpi=110)
        plt.close(fig)
        written.append(name)
    return written


def trends(out_dir, results):
    densities = sorted({r["density"] for r in results if r["density"] >= 0})
    if len(densities) < 2:
        return []
    methods = list(dict.fromkeys(r["method"] for r in results))
    metrics = [("flight_time_s", "Flight time (s)", 0), ("distance_m", "Flight distance (m)", 1),
               ("energy", "Energy (m²/s⁵)", 2), ("iterations", "Planning iterations", 3)]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for ax, (key, label, paper_idx) in zip(axes.flat, metrics):
        for m in methods:
            ys, es = [], []
            for d in densities:
                mu, sd = mean_std([r[key] for r in results
                                   if r["method"] == m and r["density"] == d and r["success"]])
                ys.append(mu)
                es.append(sd)
            ax.errorbar(densities, ys, yerr=es, marker="o", capsize=3, label=m,
                        color=COLORS.get(m, None))
        paper = [PAPER_MMH[d][paper_idx] if d in PAPER_MMH else float("nan") for d in densities]
        ax.plot(densities, paper, "k--", marker="x", label="paper MMH")
        ax.set_xlabel("obstacle density (obs/m²)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Performance over obstacle density (successful flights, mean ± std)")
    fig.tight_layout()
    name = os.path.join(out_dir, "trends.png")
    fig.savefig(name, dpi=110)
    plt.close(fig)
    return [name]


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "results.json")) as fh:
        results = json.load(fh)
    written = top_views(out_dir, results) + trends(out_dir, results)
    for w in written:
        print("plot:", w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
