#!/usr/bin/python3
"""Hem height and number of folds of draped specimens (a fabric sweep).

For each output folder of `sartor run` on a Cusick case (OUTDIR/result.h5,
OUTDIR/summary.json): the rim is the boundary of the specimen's mesh (edges
of one triangle). Hem height: the mean and the lowest z of the rim vertices
(m). Folds: the rim's distance from the axis r(theta), less its mean,
smoothed by a circular moving average over --smooth vertices; each fold is
one outward lobe: a local maximum standing more than --min-amplitude (m)
above the valleys on both sides (shallower ones are merged into their
neighbours). Prints a table, writes
--json (the numbers) and --output (a PNG: each specimen seen from above,
coloured by height, with its rim). The drape coefficient comes from the
summary (contact.drape.coefficient) when the case reports it.

Needs numpy, matplotlib and h5py; run it with /usr/bin/python3.
"""

import argparse
import json
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure
from sartor_render import read_result

import numpy as np


def rim_vertices(triangles):
    """Vertices on edges that belong to one triangle only."""
    count = {}
    for t in triangles:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    return sorted({v for edge, n in count.items() if n == 1 for v in edge})


def count_folds(theta, radius, smooth, min_amplitude):
    """Outward lobes of r(theta) around the circle: local maxima whose
    prominence (height above the higher of the two valleys beside them)
    exceeds min_amplitude."""
    order = np.argsort(theta)
    r = radius[order]
    if smooth > 1:
        kernel = np.ones(smooth) / smooth
        padded = np.concatenate([r[-smooth:], r, r[:smooth]])
        r = np.convolve(padded, kernel, mode="same")[smooth:-smooth]
    n = len(r)
    peaks = [i for i in range(n) if r[i] > r[i - 1] and r[i] >= r[(i + 1) % n]]
    valleys = [i for i in range(n) if r[i] < r[i - 1] and r[i] <= r[(i + 1) % n]]
    if not peaks or not valleys:
        return 0
    # Merge maxima whose valley between them is shallow until all remaining
    # peaks stand min_amplitude above both neighbouring valleys.
    extrema = sorted([(i, +1) for i in peaks] + [(i, -1) for i in valleys])
    values = [r[i] for i, _ in extrema]
    kinds = [k for _, k in extrema]
    changed = True
    while changed and kinds.count(1) > 1:
        changed = False
        m = len(kinds)
        for j in range(m):
            if kinds[j] != 1:
                continue
            left, right = values[j - 1], values[(j + 1) % m]
            if values[j] - max(left, right) < min_amplitude:
                # Drop the peak and its higher neighbouring valley.
                drop = (j - 1) % m if left > right else (j + 1) % m
                for index in sorted({j, drop}, reverse=True):
                    del values[index]
                    del kinds[index]
                changed = True
                break
    return kinds.count(1)


def measure(folder, smooth, min_amplitude):
    positions, triangles, _, fabrics = read_result(os.path.join(folder, "result.h5"))
    rim = rim_vertices(triangles)
    p = positions[rim]
    theta = np.arctan2(p[:, 1], p[:, 0])
    radius = np.hypot(p[:, 0], p[:, 1])
    summary = read_json(os.path.join(folder, "summary.json"))
    drape = summary.get("contact", {}).get("drape", {})
    return {
        "folder": folder,
        "fabrics": fabrics,
        "hem_height_mean_m": float(p[:, 2].mean()),
        "hem_height_min_m": float(p[:, 2].min()),
        "rim_radius_mean_m": float(radius.mean()),
        "folds": count_folds(theta, radius, smooth, min_amplitude),
        "drape_coefficient": drape.get("coefficient"),
        "rim_vertices": len(rim),
    }, positions, triangles, rim


def plot(results, output):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(results), figsize=(4.2 * len(results), 4.4), squeeze=False)
    low = min(r[1][:, 2].min() for r in results)
    for ax, (numbers, positions, triangles, rim) in zip(axes[0], results):
        shade = ax.tripcolor(positions[:, 0], positions[:, 1], triangles, positions[:, 2],
                             shading="gouraud", cmap="viridis", vmin=low, vmax=0.0)
        ordered = sorted(rim, key=lambda v: np.arctan2(positions[v, 1], positions[v, 0]))
        ring = positions[ordered + ordered[:1]]
        ax.plot(ring[:, 0], ring[:, 1], "k-", lw=0.8)
        ax.set_aspect("equal")
        ax.set_title("%s\nhem %.3f m, %d folds%s" % (
            os.path.basename(os.path.normpath(numbers["folder"])), numbers["hem_height_mean_m"],
            numbers["folds"],
            "" if numbers["drape_coefficient"] is None else ", DC %.2f" % numbers["drape_coefficient"]),
            fontsize=9)
        ax.set_xlabel("x (m)")
    axes[0][0].set_ylabel("y (m)")
    fig.colorbar(shade, ax=list(axes[0]), label="z (m)", shrink=0.8)
    save_figure(fig, output, 150)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folders", nargs="+", help="output folders of sartor run")
    parser.add_argument("--smooth", type=int, default=3, help="moving-average width, vertices [3]")
    parser.add_argument("--min-amplitude", type=float, default=0.002,
                        help="smallest lobe counted as a fold, m [0.002]")
    parser.add_argument("--json", help="write the numbers here")
    parser.add_argument("--output", help="write the picture here (PNG)")
    args = parser.parse_args()
    try:
        results = [measure(f, args.smooth, args.min_amplitude) for f in args.folders]
    except PlotError as error:
        sys.exit("fabric_sweep.py: %s" % error)
    print("%-28s %10s %10s %6s %6s" % ("case", "hem mean", "hem min", "folds", "DC"))
    for numbers, *_ in results:
        dc = numbers["drape_coefficient"]
        print("%-28s %10.4f %10.4f %6d %6s" % (
            os.path.basename(os.path.normpath(numbers["folder"])), numbers["hem_height_mean_m"],
            numbers["hem_height_min_m"], numbers["folds"], "-" if dc is None else "%.3f" % dc))
    if args.json:
        with open(args.json, "w") as f:
            json.dump([r[0] for r in results], f, indent=2)
    if args.output:
        plot(results, args.output)


if __name__ == "__main__":
    main()
