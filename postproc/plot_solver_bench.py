#!/usr/bin/python3
"""Plot the solver benchmark written by tests/bench/run_solver_bench.py.

Reads OUTDIR/solver_bench.json and writes OUTDIR/solver_bench.png (150 dpi),
three panels against the number of vertices, log-log, one colour per series
(garment, sphere drape, Hencky disk), solid lines for 1 rank and dashed for
more:

* (a) CPU time (user + sys of the run's process tree), with the least-squares
  growth exponent of each series in the legend and an n^1.2 guide;
* (b) Newton iterations (of the whole run: a drape's time steps and settle);
* (c) peak resident memory per vertex (the largest process times the ranks).

Runs that failed or were not certified have open markers; runs past the time
limit are marked with an x at the limit on (a). Needs numpy and matplotlib;
run it with /usr/bin/python3.
"""

import argparse
import math
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PROGRAM = "plot_solver_bench.py"
DPI = 150


def growth_exponent(vertices, times):
    """Least-squares slope of log time against log vertices (None below two points)."""
    if len(vertices) < 2:
        return None
    slope, _ = np.polyfit(np.log(vertices), np.log(times), 1)
    return slope


def draw(runs, limit, output):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    series = sorted({run["series"] for run in runs})
    colours = plt.get_cmap("tab10")
    for index, name in enumerate(series):
        colour = colours(index % 10)
        for ranks in sorted({run["ranks"] for run in runs if run["series"] == name}):
            done = [r for r in runs if r["series"] == name and r["ranks"] == ranks
                    and r.get("vertices") and r["status"] in ("ok", "failed")]
            done.sort(key=lambda r: r["vertices"])
            style = "-" if ranks == 1 else "--"
            if done:
                n = np.array([r["vertices"] for r in done], dtype=float)
                cpu = np.array([r["cpu_s"] for r in done])
                exponent = growth_exponent(n, cpu)
                label = f"{name}, {ranks} rank{'s' if ranks > 1 else ''}"
                if exponent is not None:
                    label += f" (n^{exponent:.2f})"
                good = [r["status"] == "ok" and r.get("certificate") == "certified" for r in done]
                for ax, values in ((axes[0], cpu),
                                   (axes[1], [r.get("newton_iterations") or np.nan for r in done]),
                                   (axes[2], [r.get("bytes_per_vertex") or np.nan for r in done])):
                    ax.plot(n, values, style, color=colour, label=label if ax is axes[0] else None)
                    for x, y, filled in zip(n, values, good):
                        ax.plot([x], [y], "o", color=colour,
                                markerfacecolor=colour if filled else "none")
            for r in runs:
                if r["series"] == name and r["ranks"] == ranks and r["status"] == "timeout" \
                        and done:
                    axes[0].plot([done[-1]["vertices"] * 4], [limit], "x", color=colour)
    all_n = [r["vertices"] for r in runs if r.get("vertices")]
    all_cpu = [r["cpu_s"] for r in runs if r.get("vertices")]
    if all_n:
        n0, t0 = min(all_n), min(all_cpu)
        guide = np.array([n0, max(all_n) * 4])
        axes[0].plot(guide, t0 * (guide / n0) ** 1.2, ":", color="grey", label="n^1.2")
    titles = ("(a) CPU time, s (user + sys)", "(b) Newton iterations",
              "(c) peak memory per vertex, bytes")
    for ax, title in zip(axes, titles):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("vertices")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Sartor solver benchmark (open markers: not certified or failed; "
                 f"x: past the {limit:g} s limit)")
    fig.tight_layout()
    save_figure(fig, output, DPI)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="the benchmark's output folder (solver_bench.json)")
    arguments = parser.parse_args()
    try:
        document = read_json(os.path.join(arguments.outdir, "solver_bench.json"))
        runs = document.get("runs", [])
        if not any(r.get("vertices") for r in runs):
            raise PlotError(f"{arguments.outdir}/solver_bench.json: no run with results")
        limit = document.get("host", {}).get("time_limit_s", math.nan)
        output = os.path.join(arguments.outdir, "solver_bench.png")
        draw(runs, limit, output)
    except PlotError as error:
        print(f"{PROGRAM}: {error}", file=sys.stderr)
        return 1
    print(f"{PROGRAM}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
