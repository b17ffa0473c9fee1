#!/usr/bin/python3
"""Plot the finite-element benchmark written by tests/bench/run_fe_benchmark.sh.

Reads OUTDIR/fe_benchmark.csv (one row per mesh size and rank count, as
sartor-bench-fe --csv writes it) and, when present, OUTDIR/fe_benchmark.json
(for the solver and host in the title), and writes one PNG (150 dpi):

* (a) solve and setup time against the number of triangles, log-log, one
  colour per rank count, with an n^1.2 guide line (dashed, the growth target;
  --exponent changes it) and n^1 (dotted) through the smallest 1-rank solve,
  and the target "10^4 vertices in under 1 s on one core" as a star; the legend
  gives the least-squares growth exponent of each solve-time curve;
* (b) assembly cost per triangle (core time: wall time x ranks / triangles)
  of one residual and one Jacobian;
* (c) Newton iterations and linear iterations per Newton iteration;
* (d) peak resident memory per vertex, summed over the ranks.

Runs that did not converge are drawn with open markers. The exponents are
also printed. Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import math
import os
import sys

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure

import numpy as np
import matplotlib.pyplot as plt

PROGRAM = "plot_fe_benchmark.py"
DPI = 150
CSV_COLUMNS = (
    "triangles", "vertices", "ranks", "setup_s", "solve_s", "residual_ns_per_triangle",
    "jacobian_ns_per_triangle", "newton_iterations", "linear_iterations", "converged",
    "bytes_per_vertex",
)
TARGET_VERTICES = 1e4  # a 10K-vertex static solve ...
TARGET_SECONDS = 1.0   # ... in under 1 s on one core
COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")


def read_benchmark(outdir):
    if not os.path.isdir(outdir):
        raise PlotError("%s: no such folder (expected the output folder of run_fe_benchmark.sh)"
                        % outdir)
    csv_path = os.path.join(outdir, "fe_benchmark.csv")
    if not os.path.isfile(csv_path):
        raise PlotError("%s: no such file (is %s an output folder of run_fe_benchmark.sh?)"
                        % (csv_path, outdir))
    data = read_csv_columns(csv_path, CSV_COLUMNS)
    if np.any(data["triangles"] <= 0) or np.any(data["ranks"] < 1):
        raise PlotError("%s: triangles and ranks must be positive" % csv_path)
    json_path = os.path.join(outdir, "fe_benchmark.json")
    document = read_json(json_path) if os.path.isfile(json_path) else {}
    return data, document


def describe_runs(document):
    """'solver on host' from the JSON documents, or ''."""
    runs = document.get("runs") if isinstance(document, dict) else None
    if not isinstance(runs, list) or not runs or not isinstance(runs[0], dict):
        return ""
    solvers = sorted({str(run.get("solver")) for run in runs if isinstance(run, dict)})
    hosts = sorted({str(run.get("host")) for run in runs if isinstance(run, dict)})
    threads = runs[0].get("hardware_threads")
    text = "solver %s" % ", ".join(solvers)
    if hosts:
        text += " on %s" % ", ".join(hosts)
        if isinstance(threads, int):
            text += " (%d hardware threads)" % threads
    return text


def growth_exponent(x, y):
    """Least-squares slope of log y against log x, or None for fewer than two sizes."""
    keep = (x > 0) & (y > 0)
    if np.unique(x[keep]).size < 2:
        return None
    return float(np.polyfit(np.log(x[keep]), np.log(y[keep]), 1)[0])


def rank_groups(data):
    """(ranks, row indices sorted by triangles, colour) for every rank count."""
    groups = []
    for k, ranks in enumerate(np.unique(data["ranks"])):
        rows = np.nonzero(data["ranks"] == ranks)[0]
        rows = rows[np.argsort(data["triangles"][rows], kind="stable")]
        groups.append((int(ranks), rows, COLOURS[k % len(COLOURS)]))
    return groups


def rank_label(ranks):
    return "%d rank%s" % (ranks, "" if ranks == 1 else "s")


def plot_series(axis, x, y, converged, colour, marker, style, label):
    """A line through all points; filled markers where the solve converged."""
    axis.plot(x, y, style, color=colour, lw=1.4, label=label)
    ok = converged > 0
    axis.plot(x[ok], y[ok], marker, color=colour, ms=6, ls="none")
    axis.plot(x[~ok], y[~ok], marker, color=colour, ms=6, ls="none", mfc="white")


def draw_times(axis, data, groups, exponent):
    exponents = {}
    for ranks, rows, colour in groups:
        triangles = data["triangles"][rows]
        slope = growth_exponent(triangles, data["solve_s"][rows])
        exponents[ranks] = slope
        label = "solve, %s" % rank_label(ranks)
        if slope is not None:
            label += r" ($\propto n^{%.2f}$)" % slope
        plot_series(axis, triangles, data["solve_s"][rows], data["converged"][rows], colour, "o",
                    "-", label)
        plot_series(axis, triangles, data["setup_s"][rows], data["converged"][rows], colour, "s",
                    "--", "setup, %s" % rank_label(ranks))
    # Guide lines through the smallest solve of the fewest ranks.
    ranks, rows, _ = groups[0]
    x0, y0 = data["triangles"][rows[0]], data["solve_s"][rows[0]]
    span = np.array([data["triangles"].min(), data["triangles"].max()])
    if span[1] > span[0] and y0 > 0:
        axis.plot(span, y0 * (span / x0) ** exponent, color="black", lw=1.0, ls=(0, (6, 3)),
                  label=r"$n^{%g}$ (target growth)" % exponent)
        axis.plot(span, y0 * (span / x0), color="0.5", lw=1.0, ls=":", label=r"$n^{1}$")
    # The target: a 10K-vertex solve under 1 s on one core (2 n^2 triangles, (n+1)^2 vertices).
    side = math.sqrt(TARGET_VERTICES) - 1.0
    axis.plot([2.0 * side * side], [TARGET_SECONDS], "*", color="tab:red", ms=12, ls="none",
              label=r"target: $10^4$ vertices < 1 s (1 core)")
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xlabel("triangles")
    axis.set_ylabel("wall time (s)")
    axis.set_title("(a) Static solve and setup time", loc="left")
    axis.grid(True, which="major", alpha=0.35)
    axis.grid(True, which="minor", alpha=0.12)
    axis.legend(loc="upper left", fontsize="x-small", framealpha=0.85)
    return exponents


def draw_assembly(axis, data, groups):
    for ranks, rows, colour in groups:
        triangles = data["triangles"][rows]
        converged = data["converged"][rows]
        plot_series(axis, triangles, data["residual_ns_per_triangle"][rows], converged, colour,
                    "o", "-", "residual, %s" % rank_label(ranks))
        plot_series(axis, triangles, data["jacobian_ns_per_triangle"][rows], converged, colour,
                    "^", "--", "Jacobian, %s" % rank_label(ranks))
    axis.set_xscale("log")
    axis.set_ylim(bottom=0)
    axis.set_xlabel("triangles")
    axis.set_ylabel("core time per triangle (ns)")
    axis.set_title("(b) Assembly cost (membrane + bending + gravity)", loc="left")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(loc="best", fontsize="x-small", framealpha=0.85)


def draw_iterations(axis, data, groups):
    twin = axis.twinx()
    for ranks, rows, colour in groups:
        triangles = data["triangles"][rows]
        converged = data["converged"][rows]
        newton = data["newton_iterations"][rows]
        per_newton = data["linear_iterations"][rows] / np.maximum(newton, 1)
        plot_series(axis, triangles, newton, converged, colour, "o", "-",
                    "Newton, %s" % rank_label(ranks))
        plot_series(twin, triangles, per_newton, converged, colour, "D", "--",
                    "linear per Newton, %s" % rank_label(ranks))
    axis.set_xscale("log")
    axis.set_ylim(bottom=0)
    twin.set_ylim(bottom=0)
    axis.set_xlabel("triangles")
    axis.set_ylabel("Newton iterations (solid)")
    twin.set_ylabel("linear iterations per Newton iteration (dashed)")
    axis.set_title("(c) Iterations", loc="left")
    axis.grid(True, which="both", alpha=0.3)
    lines = axis.get_legend_handles_labels()
    twin_lines = twin.get_legend_handles_labels()
    axis.legend(lines[0] + twin_lines[0], lines[1] + twin_lines[1], loc="best",
                fontsize="x-small", framealpha=0.85)


def draw_memory(axis, data, groups):
    for ranks, rows, colour in groups:
        plot_series(axis, data["vertices"][rows], data["bytes_per_vertex"][rows] / 1024.0,
                    data["converged"][rows], colour, "o", "-", rank_label(ranks))
    axis.set_xscale("log")
    axis.set_ylim(bottom=0)
    axis.set_xlabel("vertices")
    axis.set_ylabel("peak memory per vertex (KiB)")
    axis.set_title("(d) Memory (peak RSS over start, summed over ranks)", loc="left")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(loc="best", fontsize="x-small", framealpha=0.85)


def make_figure(data, document, title, exponent):
    groups = rank_groups(data)
    fig, axes = plt.subplots(2, 2, figsize=(13, 9.5), layout="constrained")
    exponents = draw_times(axes[0, 0], data, groups, exponent)
    draw_assembly(axes[0, 1], data, groups)
    draw_iterations(axes[1, 0], data, groups)
    draw_memory(axes[1, 1], data, groups)
    if title is None:
        title = "Hanging-sheet static solve: performance"
        details = describe_runs(document)
        if details:
            title += "\n" + details
    fig.suptitle(title, fontsize=13)
    if np.any(data["converged"] <= 0):
        fig.text(0.5, 0.005, "open markers: the solve did not converge", ha="center",
                 va="bottom", fontsize=9, color="tab:red")
    return fig, exponents


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot the finite-element benchmark: the output folder of "
        "tests/bench/run_fe_benchmark.sh (fe_benchmark.csv, fe_benchmark.json).",
        epilog="Also prints the least-squares growth exponent of the solve time per rank "
        "count. Run with /usr/bin/python3.",
    )
    parser.add_argument("outdir", metavar="OUTDIR", help="output folder of run_fe_benchmark.sh")
    parser.add_argument(
        "--output", "-o", metavar="FILE.png",
        help="where to write the figure (default: OUTDIR/fe_benchmark.png)",
    )
    parser.add_argument(
        "--exponent", type=float, default=1.2, metavar="P",
        help="exponent of the guide line n^P in panel (a) (default: 1.2, the growth target)",
    )
    parser.add_argument("--title", help="figure title")
    args = parser.parse_args(argv)
    if not 0 < args.exponent < 10:
        parser.error("--exponent must be between 0 and 10")

    try:
        data, document = read_benchmark(args.outdir)
        output = args.output or os.path.join(args.outdir, "fe_benchmark.png")
        fig, exponents = make_figure(data, document, args.title, args.exponent)
        try:
            save_figure(fig, output, DPI)
        finally:
            plt.close(fig)
    except PlotError as error:
        print("%s: error: %s" % (PROGRAM, error), file=sys.stderr)
        return 1
    for ranks, slope in sorted(exponents.items()):
        if slope is not None:
            print("solve time ~ n^%.2f (%s)" % (slope, rank_label(ranks)))
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
