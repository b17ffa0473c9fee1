#!/usr/bin/python3
"""Plot a mesh-refinement study written by `sartor converge`.

Reads OUTDIR/convergence.json and OUTDIR/convergence.csv and writes one PNG
(150 dpi) with two panels:

* left, log-log: the error against the mesh size h, with the least-squares
  line error = C h^p ("fitted slope p") and the observed order between
  consecutive levels written beside each segment; grey guide slopes 1 and 2
  through the finest point. With a reference value the error is
  |q - reference|; without one (self-convergence) it is the change from the
  previous level, |q_k - q_(k-1)|, plotted at h_k;
* right: the quantity itself against h (linear axes, h down to 0), with the
  reference value (solid line) or the Richardson-extrapolated estimate of the
  finest three levels (a star at h = 0, dashed line) when the study has one.

With a single level only the right panel is drawn. Warnings (an incomplete
study, a level that did not converge, a probe that is not one point) are
printed in red under the title.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import math
import os
import sys

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure

import numpy as np
import matplotlib.pyplot as plt

PROGRAM = "plot_converge.py"
DPI = 150
CSV_COLUMNS = ("level", "h", "triangles", "dofs", "value", "error", "newton_iterations",
               "solve_time_s")


def number(value):
    """A finite float, or None."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def read_study(outdir):
    if not os.path.isdir(outdir):
        raise PlotError(
            "%s: no such folder (expected the output folder of `sartor converge`)" % outdir)
    json_path = os.path.join(outdir, "convergence.json")
    csv_path = os.path.join(outdir, "convergence.csv")
    for path in (json_path, csv_path):
        if not os.path.isfile(path):
            raise PlotError(
                "%s: no such file (is %s an output folder of `sartor converge`?)" % (path, outdir))
    study = read_json(json_path)
    if not isinstance(study, dict):
        raise PlotError("%s: expected a JSON object" % json_path)
    if not isinstance(study.get("rows"), list):
        raise PlotError("%s: no 'rows' array" % json_path)
    data = read_csv_columns(csv_path, CSV_COLUMNS)
    h = data["h"]
    if np.any(~np.isfinite(h)) or np.any(h <= 0):
        raise PlotError("%s: column h must hold positive numbers" % csv_path)
    if np.any(np.diff(h) >= 0):
        raise PlotError("%s: h must decrease from level to level" % csv_path)
    if np.any(~np.isfinite(data["value"])):
        raise PlotError("%s: column value must hold finite numbers" % csv_path)
    if len(study["rows"]) != h.size:
        raise PlotError("%s has %d rows but %s has %d"
                        % (json_path, len(study["rows"]), csv_path, h.size))
    return study, data


def quantity_label(study):
    quantity = study.get("quantity") or {}
    name = quantity.get("name") or "value"
    unit = quantity.get("unit") or ""
    return name, unit


def warnings_of(study):
    lines = []
    if study.get("complete") is False:
        lines.append("incomplete study: %d of %s level(s)"
                     % (len(study["rows"]), study.get("levels", "?")))
    for row in study["rows"]:
        if row.get("converged") is False:
            lines.append("level %s did not converge" % row.get("level"))
    for warning in study.get("warnings") or []:
        lines.append(str(warning))
    return lines


def format_order(order):
    return "n/a" if order is None else "%.2f" % order


def plot_error(axis, study, data):
    """Error (or change) against h on log axes with the fitted slope."""
    reference = number(study.get("reference"))
    h, error = data["h"], data["error"]
    valid = np.isfinite(error) & (error > 0)
    name, unit = quantity_label(study)
    if reference is not None:
        axis.set_title("error |%s − reference|" % name, loc="left")
        ylabel = "error (%s)" % unit if unit else "error"
    else:
        axis.set_title("self-convergence: change from the previous level", loc="left")
        ylabel = "|%s(level k) − %s(level k−1)|%s" % (name, name, " (%s)" % unit if unit else "")
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xlabel("mesh size h (m, longest material edge)")
    axis.set_ylabel(ylabel)
    axis.grid(True, which="major", alpha=0.35)
    axis.grid(True, which="minor", alpha=0.12)
    if not np.any(valid):
        axis.text(0.5, 0.5, "no nonzero errors to plot", ha="center", va="center",
                  transform=axis.transAxes, color="0.4")
        return
    axis.plot(h[valid], error[valid], "o-", color="tab:blue", lw=1.4, ms=6, label="levels")
    for k, level in enumerate(data["level"]):
        if valid[k]:
            axis.annotate("%d" % level, (h[k], error[k]), textcoords="offset points",
                          xytext=(5, -11), fontsize="x-small", color="tab:blue")
    # observed orders of consecutive levels, beside each segment
    orders = study.get("orders") if reference is not None else None
    if orders:
        for entry in orders:
            levels = entry.get("levels") or []
            order = number(entry.get("order"))
            if len(levels) != 2 or order is None:
                continue
            i, j = int(levels[0]), int(levels[1])
            if j < h.size and valid[i] and valid[j]:
                x = math.sqrt(h[i] * h[j])
                y = math.sqrt(error[i] * error[j])
                axis.annotate("p = %.2f" % order, (x, y), textcoords="offset points",
                              xytext=(-58, 4), fontsize="small", color="0.25",
                              bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none",
                                        alpha=0.8))
    fit = study.get("fit") or {}
    order, constant = number(fit.get("order")), number(fit.get("constant"))
    if order is not None and constant is not None and np.count_nonzero(valid) >= 2:
        span = np.array([h[valid].min() / 1.3, h[valid].max() * 1.3])
        axis.plot(span, constant * span ** order, "--", color="tab:red", lw=1.2,
                  label="fitted slope %.2f" % order)
    # guide slopes through the finest valid point
    finest = np.nonzero(valid)[0][-1]
    span = np.array([h[valid].min(), h[valid].max()])
    for slope, style in ((1, ":"), (2, "-.")):
        axis.plot(span, error[finest] * (span / h[finest]) ** slope, style, color="0.6", lw=0.9,
                  label="slope %d" % slope)
    axis.legend(loc="lower right", fontsize="small", framealpha=0.85)


def plot_value(axis, study, data):
    """The quantity against h, with the reference or the Richardson estimate."""
    name, unit = quantity_label(study)
    h, value = data["h"], data["value"]
    axis.set_title("%s against the mesh size" % name, loc="left")
    axis.plot(h, value, "o-", color="tab:blue", lw=1.4, ms=6, label=name)
    reference = number(study.get("reference"))
    if reference is not None:
        axis.axhline(reference, color="black", lw=1.0, label="reference %.6g" % reference)
    estimate = None
    for triplet in study.get("self_convergence") or []:
        value_ = number(triplet.get("richardson_estimate"))
        if value_ is not None:
            estimate = (value_, triplet)
    if estimate is not None:
        value_, triplet = estimate
        levels = triplet.get("levels") or []
        label = "Richardson estimate %.6g" % value_
        if len(levels) == 3:
            label += " (levels %s, p = %s)" % ("-".join(str(l) for l in levels),
                                               format_order(number(triplet.get("order"))))
        axis.plot([0.0], [value_], "*", color="tab:red", ms=11, label=label)
        axis.plot([0.0, h[-1]], [value_, value[-1]], "--", color="tab:red", lw=0.9)
    axis.set_xlim(left=0.0, right=1.05 * h.max())
    axis.set_xlabel("mesh size h (m, longest material edge)")
    axis.set_ylabel("%s (%s)" % (name, unit) if unit else name)
    axis.grid(True, alpha=0.35)
    axis.ticklabel_format(axis="y", style="plain", useOffset=False)
    axis.legend(loc="best", fontsize="small", framealpha=0.85)


def make_figure(study, data, title):
    warnings = warnings_of(study)
    single = data["h"].size < 2
    fig, axes = plt.subplots(1, 1 if single else 2, figsize=(6.5 if single else 12.5, 5.2),
                             squeeze=False)
    axes = axes[0]
    if single:
        plot_value(axes[0], study, data)
    else:
        plot_error(axes[0], study, data)
        plot_value(axes[1], study, data)
    name, _ = quantity_label(study)
    if title is None:
        case = os.path.basename(str(study.get("case") or "case"))
        rows = study["rows"]
        triangles = "%s–%s triangles" % (rows[0].get("triangles", "?"),
                                         rows[-1].get("triangles", "?"))
        title = "sartor converge: %s, %s, %d level(s), %s" % (case, name, len(rows), triangles)
    fig.suptitle(title, fontsize="medium", y=0.985)
    top = 0.95
    if warnings:
        fig.text(0.5, 0.935, "; ".join(warnings), ha="center", va="center", color="tab:red",
                 fontsize="small", wrap=True)
        top = 0.91
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot a mesh-refinement study: the output folder of `sartor converge` "
        "(convergence.json and convergence.csv).",
        epilog="Left: error (or level-to-level change) against h on log axes with the fitted "
        "slope; right: the quantity against h with the reference or the Richardson estimate. "
        "Run with /usr/bin/python3.",
    )
    parser.add_argument("outdir", metavar="OUTDIR", help="output folder of `sartor converge`")
    parser.add_argument(
        "--output", "-o", metavar="FILE.png",
        help="where to write the figure (default: OUTDIR/convergence.png)",
    )
    parser.add_argument("--title", help="figure title (default: case, quantity, levels)")
    args = parser.parse_args(argv)

    try:
        study, data = read_study(args.outdir)
        output = args.output or os.path.join(args.outdir, "convergence.png")
        fig = make_figure(study, data, args.title)
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
