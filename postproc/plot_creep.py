#!/usr/bin/python3
"""Plot the strip creep responses written by `sartor creep`.

Reads OUTDIR/summary.json and the per-run CSV files it names, and writes one
PNG (150 dpi):

* constant-force creep-and-recovery runs (load kind "creep_recovery"): total
  elongation in % against the time since load application (loading panel) and
  since load removal (unloading panel), both on a logarithmic time axis, in the
  layout of the thesis' Fig. 5.9; with warp and weft runs present the figure
  has four panels (a) loading-warp, (b) unloading-warp, (c) loading-weft,
  (d) unloading-weft, one colour per fabric. Thin dashed lines in the unloading
  panels show the permanent part eps_p (--no-permanent hides them).
* tension-history runs (load kind "history"): one panel per run on a linear
  time axis with the total strain, its three components and, on a second
  axis, the tension.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure, time_unit

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.gridspec import GridSpec

PROGRAM = "plot_creep.py"
DPI = 150
CSV_COLUMNS = (
    "time_s",
    "tension_N_per_m",
    "strain_total",
    "strain_elastic",
    "strain_viscoelastic",
    "strain_permanent",
)
DIRECTIONS = ("warp", "weft")


# --------------------------------------------------------------------------
# Input


class Run:
    def __init__(self, outdir, entry, position):
        if not isinstance(entry, dict):
            raise PlotError("summary.json: runs[%d] is not an object" % position)
        self.name = str(entry.get("name") or "run %d" % (position + 1))
        name_parts = self.name.split(":")
        self.fabric = str(entry.get("fabric") or name_parts[0])
        direction = entry.get("direction")
        if not direction and len(name_parts) > 1:
            direction = name_parts[-1]
        self.direction = direction if direction in DIRECTIONS else None
        if not entry.get("csv"):
            raise PlotError("summary.json: run '%s' names no csv file" % self.name)
        self.csv = os.path.join(outdir, str(entry["csv"]))
        load = entry.get("load") or {}
        self.load = load if isinstance(load, dict) else {}
        self.kind = self.load.get("kind", "history")
        self.data = read_csv_columns(self.csv, CSV_COLUMNS)
        time = self.data["time_s"]
        if np.any(np.diff(time) < 0):
            raise PlotError("%s: time_s is not sorted" % self.csv)

    def load_times(self):
        """(t_on, t_off) of a creep-and-recovery run; t_off None without unloading."""
        time = self.data["time_s"]
        tension = self.data["tension_N_per_m"]
        loaded = np.nonzero(tension > 0)[0]
        if loaded.size == 0:
            raise PlotError("%s: a creep_recovery run with no positive tension" % self.csv)
        t_on = time[loaded[0]]
        duration = self.load.get("load_duration_s")
        if isinstance(duration, (int, float)) and duration > 0:
            t_off = t_on + float(duration)
        else:
            unloaded = np.nonzero((time > t_on) & (tension <= 0))[0]
            t_off = time[unloaded[0]] if unloaded.size else None
        if t_off is not None and t_off >= time[-1] and not np.any(
            (time >= t_off) & (tension <= 0)
        ):
            t_off = None
        return t_on, t_off


def read_summary(outdir):
    if not os.path.isdir(outdir):
        raise PlotError("%s: no such folder (expected the output folder of `sartor creep`)" % outdir)
    path = os.path.join(outdir, "summary.json")
    if not os.path.isfile(path):
        raise PlotError("%s: no such file (is %s an output folder of `sartor creep`?)" % (path, outdir))
    summary = read_json(path)
    if not isinstance(summary, dict):
        raise PlotError("%s: expected a JSON object" % path)
    command = summary.get("command")
    if command is not None and command != "creep":
        raise PlotError(
            "%s: written by `sartor %s`, not `sartor creep`%s"
            % (path, command, " (use plot_fit.py)" if command == "fit" else "")
        )
    entries = summary.get("runs")
    if not isinstance(entries, list) or not entries:
        raise PlotError("%s: no runs listed (key 'runs')" % path)
    return [Run(outdir, entry, k) for k, entry in enumerate(entries)]


# --------------------------------------------------------------------------
# Plotting

def percent(values):
    return 100.0 * np.asarray(values)


def fabric_colours(runs):
    fabrics = []
    for run in runs:
        if run.fabric not in fabrics:
            fabrics.append(run.fabric)
    cycle = plt.get_cmap("tab10").colors
    return {fabric: cycle[k % len(cycle)] for k, fabric in enumerate(fabrics)}


def loading_segment(run, t_on, t_off):
    data = run.data
    time = data["time_s"]
    mask = (time > t_on) & (data["tension_N_per_m"] > 0)
    if t_off is not None:
        mask &= time <= t_off
    return time[mask] - t_on, data["strain_total"][mask]


def unloading_segment(run, t_off):
    data = run.data
    time = data["time_s"]
    mask = time > t_off
    return (
        time[mask] - t_off,
        data["strain_total"][mask],
        data["strain_permanent"][mask],
    )


def describe_load(run):
    load = run.load
    parts = []
    if isinstance(load.get("tension_N_per_m"), (int, float)):
        parts.append("%.4g N/m" % load["tension_N_per_m"])
    if isinstance(load.get("load_duration_s"), (int, float)):
        parts.append("loaded %s" % format_duration(load["load_duration_s"]))
    if isinstance(load.get("recovery_duration_s"), (int, float)):
        parts.append("recovery %s" % format_duration(load["recovery_duration_s"]))
    return ", ".join(parts)


def format_duration(seconds):
    seconds = float(seconds)
    if seconds >= 3600 and abs(seconds / 3600 - round(seconds / 3600)) < 1e-9:
        return "%g h" % (seconds / 3600)
    if seconds >= 60 and abs(seconds / 60 - round(seconds / 60)) < 1e-9:
        return "%g min" % (seconds / 60)
    return "%g s" % seconds


def style_log_axis(axis, xlabel):
    axis.set_xscale("log")
    axis.set_xlabel(xlabel)
    axis.set_ylabel("elongation (%)")
    axis.grid(True, which="major", alpha=0.35)
    axis.grid(True, which="minor", alpha=0.12)


def plot_creep_recovery(fig, grid_rows, runs, show_permanent):
    """Fig. 5.9-style panels; returns the number of grid rows used."""
    colours = fabric_colours(runs)
    directions = [d for d in DIRECTIONS if any(run.direction == d for run in runs)]
    split = len(directions) == 2
    groups = [(d, [run for run in runs if run.direction == d]) for d in directions] if split else [
        (None, runs)
    ]
    # Label lines by fabric when each fabric appears once per panel.
    letters = "abcdefghijklmnopqrstuvwxyz"
    panel = 0
    for row, (direction, members) in enumerate(groups):
        load_axis = fig.add_subplot(grid_rows[row, 0])
        unload_axis = fig.add_subplot(grid_rows[row, 1])
        fabrics = [run.fabric for run in members]
        by_fabric = len(set(fabrics)) == len(fabrics)
        any_unloading = False
        for run in members:
            colour = colours[run.fabric]
            label = run.fabric if by_fabric else run.name
            t_on, t_off = run.load_times()
            times, strain = loading_segment(run, t_on, t_off)
            load_axis.plot(times, percent(strain), color=colour, lw=1.6, label=label)
            if t_off is not None:
                times, strain, permanent = unloading_segment(run, t_off)
                if times.size:
                    any_unloading = True
                    unload_axis.plot(times, percent(strain), color=colour, lw=1.6, label=label)
                    if show_permanent:
                        unload_axis.plot(
                            times, percent(permanent), color=colour, lw=0.8, ls="--", alpha=0.8
                        )
        suffix = "-" + direction if direction else ""
        load_axis.set_title("(%s) Loading%s" % (letters[panel], suffix), loc="left")
        unload_axis.set_title("(%s) Unloading%s" % (letters[panel + 1], suffix), loc="left")
        panel += 2
        style_log_axis(load_axis, "time since load application (s)")
        style_log_axis(unload_axis, "time since load removal (s)")
        if not any_unloading:
            unload_axis.set_xscale("linear")
            unload_axis.set_xticks([])
            unload_axis.text(
                0.5, 0.5, "no recovery in these runs", ha="center", va="center",
                transform=unload_axis.transAxes, color="0.4",
            )
        load_axis.legend(loc="best", fontsize="small", framealpha=0.85)
        if any_unloading and show_permanent:
            unload_axis.plot([], [], color="0.3", lw=0.8, ls="--", label=r"permanent $\varepsilon_p$")
            unload_axis.plot([], [], color="0.3", lw=1.6, label="total")
            handles, labels = unload_axis.get_legend_handles_labels()
            keep = [k for k, text in enumerate(labels) if text in (r"permanent $\varepsilon_p$", "total")]
            unload_axis.legend(
                [handles[k] for k in keep], [labels[k] for k in keep],
                loc="upper right", fontsize="small", framealpha=0.85,
            )
    return len(groups)


def plot_history(fig, cell, run):
    data = run.data
    axis = fig.add_subplot(cell)
    time = data["time_s"]
    scale, unit = time_unit(time[-1] - time[0])
    t = time / scale
    axis.plot(t, percent(data["strain_total"]), color="black", lw=1.8, label="total")
    axis.plot(t, percent(data["strain_elastic"]), color="tab:blue", lw=1.2, label="immediate elastic")
    axis.plot(
        t, percent(data["strain_viscoelastic"]), color="tab:orange", lw=1.2,
        label=r"viscoelastic $\varepsilon_v$",
    )
    axis.plot(
        t, percent(data["strain_permanent"]), color="tab:green", lw=1.2,
        label=r"permanent $\varepsilon_p$",
    )
    axis.set_xlabel("time (%s)" % unit)
    axis.set_ylabel("strain (%)")
    axis.grid(True, alpha=0.3)
    tension_axis = axis.twinx()
    tension_axis.plot(
        t, data["tension_N_per_m"], color="tab:red", lw=1.0, ls=":", label="tension (right axis)"
    )
    tension_axis.set_ylabel("tension (N/m)", color="tab:red")
    tension_axis.tick_params(axis="y", colors="tab:red")
    top = max(float(np.max(data["tension_N_per_m"])), 0.0)
    bottom = min(0.0, float(np.min(data["tension_N_per_m"])))
    span = (top - bottom) if top > bottom else 1.0
    tension_axis.set_ylim(bottom - 0.04 * span, top + 0.08 * span)
    handles, labels = axis.get_legend_handles_labels()
    extra_handles, extra_labels = tension_axis.get_legend_handles_labels()
    axis.legend(handles + extra_handles, labels + extra_labels, loc="upper left",
                bbox_to_anchor=(1.09, 1.0), fontsize="small", framealpha=0.85)
    source = run.load.get("file")
    axis.set_title(
        "%s  (tension history%s)" % (run.name, ": " + os.path.basename(str(source)) if source else ""),
        loc="left",
    )


def make_figure(runs, show_permanent, title):
    creep = [run for run in runs if run.kind == "creep_recovery"]
    history = [run for run in runs if run.kind != "creep_recovery"]
    unknown = sorted({run.kind for run in history if run.kind != "history"})
    if unknown:
        print("%s: warning: unknown load kind(s) %s plotted as tension histories"
              % (PROGRAM, ", ".join(map(str, unknown))), file=sys.stderr)
    creep_rows = 0
    if creep:
        both = all(any(run.direction == d for run in creep) for d in DIRECTIONS)
        creep_rows = 2 if both else 1
    rows = creep_rows + len(history)
    heights = [1.0] * creep_rows + [0.85] * len(history)
    fig = plt.figure(figsize=(12, 1.0 + 3.9 * sum(heights)), layout="constrained")
    grid = GridSpec(rows, 2, figure=fig, height_ratios=heights)
    if creep:
        plot_creep_recovery(fig, grid, creep, show_permanent)
    for k, run in enumerate(history):
        plot_history(fig, grid[creep_rows + k, :], run)
    if title is None:
        loads = sorted({describe_load(run) for run in creep} - {""})
        title = "Constant-force creep and recovery" if creep else "Creep under a tension history"
        if len(loads) == 1:
            title += " (%s)" % loads[0]
    if title:
        fig.suptitle(title)
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot the strip creep responses in an output folder of `sartor creep` "
        "(summary.json and the CSV files it lists).",
        epilog="Creep-and-recovery runs are drawn like the thesis' Fig. 5.9 (log time axes); "
        "tension-history runs get one linear-time panel each. Run with /usr/bin/python3.",
    )
    parser.add_argument("outdir", metavar="OUTDIR", help="output folder of `sartor creep`")
    parser.add_argument(
        "--output", "-o", metavar="FILE.png",
        help="where to write the figure (default: OUTDIR/creep.png)",
    )
    parser.add_argument(
        "--no-permanent", action="store_true",
        help="do not draw the permanent strain (dashed) in the unloading panels",
    )
    parser.add_argument("--title", help="figure title (default: derived from the load; '' for none)")
    args = parser.parse_args(argv)

    try:
        runs = read_summary(args.outdir)
        output = args.output or os.path.join(args.outdir, "creep.png")
        fig = make_figure(runs, not args.no_permanent, args.title)
        try:
            save_figure(fig, output, DPI)
        finally:
            plt.close(fig)
    except PlotError as error:
        print("%s: error: %s" % (PROGRAM, error), file=sys.stderr)
        return 1
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
