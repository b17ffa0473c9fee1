#!/usr/bin/python3
"""Wear and take-off of garments (sartor drape --wear-time, docs/wear.md).

    plot_wear.py DIR [DIR ...] [--output wear.png] [--pictures PREFIX] [--state takeoff|wear]
                 [--dpi N]

Each DIR is a drape with wear: its takeoff.csv (one row per take-off),
wear.csv (one row per wear state) and summary.json (the fabrics). Draws the
hem drop and the bagging height of each take-off, and the permanent dome
height (of every wear state as a line, of the take-offs as dots) against the
wear time, one colour per DIR labelled by its fabric, into --output; with
--pictures, for each DIR the garment after its last take-off
(DIR/takeoff/series.h5) from the front and the side, coloured by the
permanent strain (the larger of warp and weft, %), into PREFIX_FABRIC.png;
with --state wear, the garment in its last worn state on the body
(DIR/wear/series.h5) instead.
Needs numpy, matplotlib and h5py (Debian python3-*).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure, time_unit  # noqa: E402


def label_of(directory):
    summary = read_json(os.path.join(directory, "summary.json"))
    fabrics = summary.get("wear", {}).get("fabrics") or summary.get("fabrics") or [directory]
    return "+".join(fabrics)


def plot_curves(directories, output, dpi):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (hem, bag, dome) = plt.subplots(1, 3, figsize=(15, 4))
    span = 0.0
    tables = []
    for directory in directories:
        path = os.path.join(directory, "takeoff.csv")
        columns = read_csv_columns(path, ["wear_time_s", "hem_drop_m", "bagging_height_m"])
        try:  # tables written before the dome height lack it
            columns.update(read_csv_columns(path, ["dome_height_m"]))
        except PlotError:
            pass
        worn = None
        try:  # every wear state's dome height, in tables written since 2026-12-07
            worn = read_csv_columns(os.path.join(directory, "wear.csv"),
                                    ["time_s", "dome_height_m"])
        except PlotError:
            pass
        tables.append((label_of(directory), columns, worn))
        span = max(span, columns["wear_time_s"].max())
    scale, unit = time_unit(span)
    for label, columns, worn in tables:
        t = columns["wear_time_s"] / scale
        hem.plot(t, 1e3 * columns["hem_drop_m"], marker="o", label=label)
        bag.plot(t, 1e3 * columns["bagging_height_m"], marker="o", label=label)
        if worn is not None:
            # On a log axis (the creep saturates within minutes of hours):
            # from the first step, not from the drape at t = 0.
            later = worn["time_s"] > 0.0
            line, = dome.plot(worn["time_s"][later] / scale, 1e3 * worn["dome_height_m"][later],
                              label=label)
            if "dome_height_m" in columns:
                dome.plot(t, 1e3 * columns["dome_height_m"], marker="o", linestyle="none",
                          color=line.get_color())
        elif "dome_height_m" in columns:
            dome.plot(t, 1e3 * columns["dome_height_m"], marker="o", label=label)
    if any(worn is not None for _, _, worn in tables):
        dome.set_xscale("log")
    hem.set_ylabel("hem drop after recovery (mm)")
    bag.set_ylabel("bagging height after recovery (mm)")
    dome.set_ylabel("permanent dome height (mm)")
    for axes in (hem, bag, dome):
        axes.set_xlabel("wear time (%s)" % unit)
        axes.grid(True, alpha=0.3)
    bag.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, output, dpi)


def read_last_state(path):
    try:
        import h5py
    except ImportError:
        raise PlotError("needs h5py (Debian: python3-h5py)")
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    with h5py.File(path, "r") as f:
        triangles = f["/mesh/triangles"][:]
        last = sorted(f["/steps"])[-1]
        step = f["/steps/" + last]
        positions = step["fields/position"][:]
        permanent = step["cell_fields/permanent"][:]
        time = float(step["time"][()])
    return positions, triangles, permanent, time


def picture(directory, output, dpi, state):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from sartor_render import add_scale_bar, draw_view

    positions, triangles, permanent, time = read_last_state(
        os.path.join(directory, state, "series.h5"))
    values = 100.0 * permanent
    top = max(values.max(), 1e-12)
    colours = plt.get_cmap("viridis")(values / top)
    fig, axes = plt.subplots(1, 2, figsize=(9, 5))
    views = [((1, 0, 0), (0, 0, 1), (0, -1, 0)), ((0, 1, 0), (0, 0, 1), (1, 0, 0))]
    for ax, view, name in zip(axes, views, ("front", "side")):
        draw_view(ax, (positions, triangles), colours, view, name)
    add_scale_bar(axes[0])
    mappable = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(0.0, top))
    fig.colorbar(mappable, ax=list(axes), label="permanent strain, larger of warp, weft (%)")
    scale, unit = time_unit(time)
    if state == "takeoff":
        title = "%s: taken off after %.3g %s of wear, hung and recovered"
    else:
        title = "%s: worn, after %.3g %s"
    fig.suptitle(title % (label_of(directory), time / scale, unit))
    save_figure(fig, output, dpi)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directories", nargs="+", metavar="DIR")
    parser.add_argument("--output", default="wear.png", help="the curves' PNG [wear.png]")
    parser.add_argument("--pictures", metavar="PREFIX",
                        help="also draw each DIR's garment after take-off into PREFIX_FABRIC.png")
    parser.add_argument("--state", choices=("takeoff", "wear"), default="takeoff",
                        help="the pictures' garment: after its last take-off, or in its last "
                        "worn state, on the body [takeoff]")
    parser.add_argument("--dpi", type=int, default=100)
    args = parser.parse_args()
    try:
        plot_curves(args.directories, args.output, args.dpi)
        if args.pictures:
            for directory in args.directories:
                picture(directory, "%s_%s.png" % (args.pictures, label_of(directory)), args.dpi,
                        args.state)
    except PlotError as error:
        sys.exit("plot_wear.py: error: %s" % error)


if __name__ == "__main__":
    main()
