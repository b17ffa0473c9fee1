#!/usr/bin/python3
"""Plot a creep-and-recovery fit written by `sartor fit`.

Reads OUTDIR/fit.json and OUTDIR/fit.csv and writes one PNG (150 dpi):

* top: the loading part against the time since load application and the
  recovery part against the time since load removal, both on a logarithmic
  time axis, with the measured samples (grey dots, thinned evenly in log time)
  and the fitted model (coloured line), plus the thesis' step-by-step
  (§5.2.2) starting estimate when fit.json has one and the test is at
  constant force (dashed; --no-estimate hides it); for a load history the
  phases are those of its largest load; a box with the fitted parameters
  (value +- standard error, confidence interval), RMSE and R^2; saturation
  warnings of the fit in red under the title;
* bottom: the residuals (% strain) against time on a linear axis, and their
  histogram with the normal density of the same standard deviation.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import math
import os
import sys
import textwrap

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure, time_unit

import numpy as np
import matplotlib.pyplot as plt
import matplotlib.ticker

PROGRAM = "plot_fit.py"
DPI = 150
CSV_COLUMNS = ("time_s", "strain_measured", "strain_fit", "residual", "phase")
PHASE_BEFORE, PHASE_LOADING, PHASE_RECOVERY = 0, 1, 2

# fit.json parameter key -> (label in mathtext, unit, description)
PARAMETERS = (
    ("elastic_modulus_N_per_m", r"$K$", "N/m", "immediate-elastic (secant) modulus"),
    ("E_N_per_m", r"$E$", "N/m", "creep modulus"),
    ("alpha", r"$\alpha$", "", "permanent share"),
    ("lambda_load_per_s", r"$\lambda_l$", "1/s", "loading rate"),
    ("lambda_unload_per_s", r"$\lambda_u$", "1/s", "recovery rate"),
)

LOAD_COLOUR = "tab:blue"
RECOVERY_COLOUR = "tab:orange"


# --------------------------------------------------------------------------
# Input


def number(value):
    """A finite float, or None."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def read_fit(outdir):
    if not os.path.isdir(outdir):
        raise PlotError("%s: no such folder (expected the output folder of `sartor fit`)" % outdir)
    json_path = os.path.join(outdir, "fit.json")
    csv_path = os.path.join(outdir, "fit.csv")
    for path in (json_path, csv_path):
        if not os.path.isfile(path):
            raise PlotError(
                "%s: no such file (is %s an output folder of `sartor fit`?)" % (path, outdir)
            )
    fit = read_json(json_path)
    if not isinstance(fit, dict):
        raise PlotError("%s: expected a JSON object" % json_path)
    if not isinstance(fit.get("parameters"), dict):
        raise PlotError("%s: no 'parameters' object" % json_path)
    data = read_csv_columns(csv_path, CSV_COLUMNS)
    time = data["time_s"]
    if np.any(np.diff(time) < 0):
        raise PlotError("%s: time_s is not sorted" % csv_path)
    phases = set(np.unique(data["phase"]).tolist())
    unknown = phases - {PHASE_BEFORE, PHASE_LOADING, PHASE_RECOVERY}
    if unknown:
        raise PlotError(
            "%s: unknown phase value(s) %s (expected 0 before loading, 1 loading, 2 recovery)"
            % (csv_path, ", ".join("%g" % p for p in sorted(unknown)))
        )
    return fit, data, csv_path


def phase_start(fit, data, key, phase):
    """Time of load application / removal: from fit.json, else the first sample of `phase`."""
    value = number((fit.get("input") or {}).get(key))
    if value is not None:
        return value
    rows = np.nonzero(data["phase"] == phase)[0]
    return float(data["time_s"][rows[0]]) if rows.size else None


# --------------------------------------------------------------------------
# Formatting


def format_value_error(value, error, unit=""):
    """'value ± error unit' rounded to two significant digits of the error."""
    unit = (" " + unit) if unit else ""
    if value is None:
        return "n/a"
    if error is None or error <= 0:
        return "%.4g%s ± n/a" % (value, unit)
    error_exponent = math.floor(math.log10(error))
    decimals = 1 - error_exponent
    value_exponent = math.floor(math.log10(abs(value))) if value != 0 else error_exponent
    if -3 <= value_exponent <= 5 and decimals <= 8:
        if decimals >= 0:
            return "%.*f ± %.*f%s" % (decimals, value, decimals, error, unit)
        step = 10.0 ** (-decimals)
        return "%.0f ± %.0f%s" % (round(value / step) * step, round(error / step) * step, unit)
    scale = 10.0 ** value_exponent
    mantissa_decimals = max(0, value_exponent - error_exponent + 1)
    return "(%.*f ± %.*f)e%+d%s" % (
        mantissa_decimals, value / scale, mantissa_decimals, error / scale, value_exponent, unit,
    )


def format_like(value, error):
    """A number rounded like format_value_error rounds values of that error."""
    if value is None:
        return "n/a"
    if error is None or error <= 0:
        return "%.4g" % value
    decimals = 1 - math.floor(math.log10(error))
    if 0 <= decimals <= 8 and (value == 0 or -3 <= math.floor(math.log10(abs(value))) <= 5):
        return "%.*f" % (decimals, value)
    if decimals < 0 and abs(value) < 1e6:
        step = 10.0 ** (-decimals)
        return "%.0f" % (round(value / step) * step)
    return "%.3g" % value


# --------------------------------------------------------------------------
# Plotting


def log_thin(offsets, limit):
    """Indices of at most `limit` samples spread evenly in log(offset)."""
    count = offsets.size
    if count <= limit:
        return np.arange(count)
    logs = np.log10(offsets)
    edges = np.linspace(logs[0], logs[-1], limit)
    chosen = np.unique(np.searchsorted(logs, edges, side="left"))
    chosen = chosen[chosen < count]
    if chosen[-1] != count - 1:
        chosen = np.append(chosen[: limit - 1], count - 1)
    return chosen


def creep_test_strain(parameters, tension, load_time, unload_time, time):
    """The closed-form constant-force creep-and-recovery response (docs/theory.md)."""
    K, E, alpha, lam_l, lam_u = parameters
    s = tension / E
    loading_offset = np.clip(time - load_time, 0.0, None)
    loading = (1.0 + tension / K) * (1.0 - s * np.expm1(-lam_l * loading_offset)) - 1.0
    c = -s * math.expm1(-lam_l * (unload_time - load_time))
    recovery = c * (alpha + (1.0 - alpha) * np.exp(-lam_u * np.clip(time - unload_time, 0.0, None)))
    return np.where(time < load_time, 0.0, np.where(time < unload_time, loading, recovery))


def thesis_curve(fit, load_time, unload_time):
    """A function time -> strain of fit.json's thesis (§5.2.2) estimate, or None."""
    estimate = fit.get("thesis_estimate")
    tension = number((fit.get("input") or {}).get("tension_N_per_m"))
    if not isinstance(estimate, dict) or tension is None or load_time is None or unload_time is None:
        return None
    # A load history's start is no constant-force curve: nothing to draw.
    if ((fit.get("input") or {}).get("load_history_knots") or 0) > 0:
        return None
    keys = ("elastic_modulus_N_per_m", "E_N_per_m", "alpha", "lambda_load_per_s",
            "lambda_unload_per_s")
    values = [number(estimate.get(key)) for key in keys]
    if any(v is None for v in values) or min(values[0], values[1], values[3], values[4]) <= 0:
        return None
    return lambda time: creep_test_strain(values, tension, load_time, unload_time, time)


def plot_phase(axis, data, start, phase, colour, limit, xlabel, title, reference=None):
    """Measured vs fitted strain of one phase on a log time axis; returns #samples shown."""
    if start is None:
        mask = np.zeros(data["time_s"].shape, dtype=bool)
    else:
        mask = (data["phase"] == phase) & (data["time_s"] > start)
    offsets = data["time_s"][mask] - (start or 0.0)
    axis.set_title(title, loc="left")
    if offsets.size == 0:
        axis.text(0.5, 0.5, "no samples in this phase", ha="center", va="center",
                  transform=axis.transAxes, color="0.4")
        axis.set_xticks([])
        axis.set_yticks([])
        return 0, 0
    order = np.argsort(offsets, kind="stable")
    offsets = offsets[order]
    measured = 100.0 * data["strain_measured"][mask][order]
    fitted = 100.0 * data["strain_fit"][mask][order]
    shown = log_thin(offsets, limit)
    axis.plot(offsets[shown], measured[shown], ".", ms=2.5, color="0.55", alpha=0.7,
              label="measured", rasterized=True)
    curve = log_thin(offsets, max(limit, 2000))
    axis.plot(offsets[curve], fitted[curve], "-", lw=1.6, color=colour, label="fit")
    if reference is not None:
        axis.plot(offsets[curve], 100.0 * reference(offsets[curve] + start), "--", lw=1.0,
                  color="black", alpha=0.75, label="thesis §5.2.2 estimate")
    axis.set_xscale("log")
    axis.set_xlabel(xlabel)
    axis.set_ylabel("elongation (%)")
    axis.grid(True, which="major", alpha=0.35)
    axis.grid(True, which="minor", alpha=0.12)
    axis.legend(loc="best", fontsize="small", markerscale=3, framealpha=0.85)
    return shown.size, offsets.size


def parameter_lines(fit):
    parameters = fit["parameters"]
    level = number(fit.get("confidence_level"))
    level_text = "%g%%" % (100 * level) if level is not None else "CI"
    lines = []
    known = {key for key, _, _, _ in PARAMETERS}
    entries = [(key, label, unit, text) for key, label, unit, text in PARAMETERS if key in parameters]
    entries += [(key, key, "", "") for key in parameters if key not in known]
    for key, label, unit, description in entries:
        entry = parameters[key]
        if not isinstance(entry, dict):
            entry = {"value": entry}
        value, error = number(entry.get("value")), number(entry.get("std_error"))
        head = "%s = %s" % (label, format_value_error(value, error, unit))
        low, high = number(entry.get("ci_low")), number(entry.get("ci_high"))
        detail = ""
        if low is not None and high is not None:
            detail = "%s CI [%s, %s]" % (level_text, format_like(low, error), format_like(high, error))
        lines.append((head, detail))
    return lines


def saturation_lines(fit, data, load_time, unload_time):
    """Saturation reached in loading and viscoelastic strain left, from the fitted rates."""
    parameters = fit["parameters"]

    def value(key):
        entry = parameters.get(key)
        return number(entry.get("value") if isinstance(entry, dict) else entry)

    lines = []
    saturation = fit.get("saturation") or {}
    lam_l, lam_u = value("lambda_load_per_s"), value("lambda_unload_per_s")
    if lam_l is not None and load_time is not None and unload_time is not None:
        t_load = unload_time - load_time
        reached = number(saturation.get("loading_saturation_fraction"))
        reached = 100 * (reached if reached is not None else -math.expm1(-lam_l * t_load))
        lines.append("loading %s: %s of saturation reached" % (
            duration_text(t_load), "> 99.99%" if reached > 99.99 else "%.4g%%" % reached))
    if lam_u is not None and unload_time is not None:
        t_rec = float(data["time_s"][-1]) - unload_time
        if t_rec > 0:
            left = number(saturation.get("recovery_remaining_fraction"))
            left = 100 * (left if left is not None else math.exp(-lam_u * t_rec))
            lines.append("recovery %s: %s of the viscoelastic strain left" % (
                duration_text(t_rec), "< 0.01%" if left < 0.01 else "%.3g%%" % left))
    return lines


def duration_text(seconds):
    scale, unit = time_unit(seconds)
    return "%.4g %s" % (seconds / scale, unit)


def draw_summary(axis, fit, data, load_time, unload_time):
    axis.axis("off")
    y = 1.0
    step = 0.052

    def put(text, size=10.5, colour="black", weight="normal", indent=0.0):
        nonlocal y
        axis.text(indent, y, text, transform=axis.transAxes, va="top", ha="left",
                  fontsize=size, color=colour, weight=weight)
        y -= step * size / 10.5

    put("Fitted parameters", weight="bold")
    for head, detail in parameter_lines(fit):
        put(head, size=10.5)
        if detail:
            put(detail, size=8.5, colour="0.35", indent=0.04)
    y -= step * 0.4
    goodness = fit.get("goodness") or {}
    rmse, r_squared = number(goodness.get("rmse")), number(goodness.get("r_squared"))
    put("Goodness of fit", weight="bold")
    if rmse is not None:
        put("RMSE = %.3g %% strain" % (100 * rmse))
    if r_squared is not None:
        put("$R^2$ = %.6f" % r_squared)
    info = fit.get("input") or {}
    samples = number(info.get("samples"))
    tension = number(info.get("tension_N_per_m"))
    details = []
    if samples is not None:
        details.append("%d samples" % samples)
    if tension is not None:
        details.append("tension %.4g N/m" % tension)
    if details:
        put(", ".join(details), size=9, colour="0.35")
    lines = saturation_lines(fit, data, load_time, unload_time)
    if lines:
        y -= step * 0.4
        put("Saturation (fitted rates)", weight="bold")
        for line in lines:
            put(line, size=9, colour="0.2")
    y -= step * 0.4
    glossary = ("K: secant immediate-elastic modulus; E: creep modulus (saturated creep = "
                "tension/E); alpha: permanent share of the creep; lambda_l, lambda_u: loading "
                "and recovery rates")
    for line in textwrap.wrap(glossary, width=62):
        put(line, size=8, colour="0.45")


def draw_residuals(axis, histogram_axis, data, load_time, unload_time):
    time = data["time_s"]
    residual = 100.0 * data["residual"]
    scale, unit = time_unit(time[-1] - time[0])
    colours = {PHASE_BEFORE: "0.5", PHASE_LOADING: LOAD_COLOUR, PHASE_RECOVERY: RECOVERY_COLOUR}
    names = {PHASE_BEFORE: "before loading", PHASE_LOADING: "loading", PHASE_RECOVERY: "recovery"}
    for phase in (PHASE_BEFORE, PHASE_LOADING, PHASE_RECOVERY):
        mask = data["phase"] == phase
        if np.any(mask):
            axis.plot(time[mask] / scale, residual[mask], ".", ms=1.5, color=colours[phase],
                      alpha=0.6, label=names[phase], rasterized=True)
    axis.axhline(0.0, color="black", lw=1.0)
    for moment in (load_time, unload_time):
        if moment is not None:
            axis.axvline(moment / scale, color="0.3", lw=0.8, ls="--")
    axis.set_xlabel("time (%s)" % unit)
    axis.set_ylabel("measured − fit (% strain)")
    axis.set_title("Residuals", loc="left")
    axis.grid(True, alpha=0.3)
    axis.legend(loc="upper right", fontsize="small", markerscale=6, framealpha=0.85)

    finite = residual[np.isfinite(residual)]
    histogram_axis.set_title("Residual distribution", loc="left")
    if finite.size < 2:
        histogram_axis.axis("off")
        return
    histogram_axis.hist(finite, bins=min(60, max(10, int(np.sqrt(finite.size)))),
                        density=True, color="0.7", edgecolor="0.5", lw=0.3)
    mean, deviation = float(np.mean(finite)), float(np.std(finite))
    if deviation > 0:
        grid = np.linspace(finite.min(), finite.max(), 200)
        density = np.exp(-0.5 * ((grid - mean) / deviation) ** 2) / (deviation * math.sqrt(2 * math.pi))
        histogram_axis.plot(grid, density, color="tab:red", lw=1.2, label="normal, same s.d.")
        histogram_axis.legend(loc="upper right", fontsize="x-small")
    histogram_axis.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(nbins=5))
    histogram_axis.set_xlabel("residual (% strain)")
    histogram_axis.set_yticks([])


def check_rmse(fit, data, csv_path):
    """Warn when fit.json's RMSE does not match the residual column."""
    rmse = number((fit.get("goodness") or {}).get("rmse"))
    residual = data["residual"][np.isfinite(data["residual"])]
    if rmse is None or residual.size == 0:
        return
    from_csv = float(np.sqrt(np.mean(residual ** 2)))
    if from_csv > 0 and abs(rmse - from_csv) > 0.05 * from_csv:
        print("%s: warning: fit.json rmse %.4g differs from the RMS of %s's residual column "
              "(%.4g)" % (PROGRAM, rmse, os.path.basename(csv_path), from_csv), file=sys.stderr)


def make_figure(fit, data, csv_path, limit, title, no_estimate=False):
    load_time = phase_start(fit, data, "load_time_s", PHASE_LOADING)
    unload_time = phase_start(fit, data, "unload_time_s", PHASE_RECOVERY)
    warnings = [str(w) for w in ((fit.get("saturation") or {}).get("warnings") or [])]
    solver = fit.get("solver") or {}
    if solver.get("converged") is False:
        warnings.insert(0, "the least-squares refinement reached no certified optimum (%s); the "
                        "parameters are the last iterate" % solver.get("reason", "unknown reason"))
    warning_lines = []
    for warning in warnings:
        warning_lines += textwrap.wrap("warning: " + warning, width=150)

    header_height = 0.45 + 0.22 * len(warning_lines)
    body_height = 8.6
    fig = plt.figure(figsize=(15, header_height + body_height), layout="constrained")
    header, body = fig.subfigures(2, 1, height_ratios=[header_height, body_height])
    if title is None:
        source = (fit.get("input") or {}).get("file")
        title = "Creep-and-recovery fit" + (": %s" % os.path.basename(str(source)) if source else "")
    header.text(0.5, 1.0 - 0.12 / header_height, title, ha="center", va="top", fontsize=14)
    for k, line in enumerate(warning_lines):
        header.text(0.5, 1.0 - (0.45 + 0.22 * k) / header_height, line, ha="center", va="top",
                    fontsize=10, color="red")

    grid = body.add_gridspec(2, 3, height_ratios=[1.35, 1.0], width_ratios=[1.0, 1.0, 0.78])
    load_axis = body.add_subplot(grid[0, 0])
    recovery_axis = body.add_subplot(grid[0, 1])
    summary_axis = body.add_subplot(grid[0, 2])
    residual_axis = body.add_subplot(grid[1, 0:2])
    histogram_axis = body.add_subplot(grid[1, 2])

    reference = None if no_estimate else thesis_curve(fit, load_time, unload_time)
    plot_phase(load_axis, data, load_time, PHASE_LOADING, LOAD_COLOUR, limit,
               "time since load application (s)", "(a) Loading", reference)
    plot_phase(recovery_axis, data, unload_time, PHASE_RECOVERY, RECOVERY_COLOUR, limit,
               "time since load removal (s)", "(b) Recovery", reference)
    draw_summary(summary_axis, fit, data, load_time, unload_time)
    draw_residuals(residual_axis, histogram_axis, data, load_time, unload_time)
    check_rmse(fit, data, csv_path)
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot a creep-and-recovery fit: the output folder of `sartor fit` "
        "(fit.json and fit.csv).",
        epilog="Measured samples are thinned evenly in log time for the top panels; the "
        "residual panel shows every sample. Run with /usr/bin/python3.",
    )
    parser.add_argument("outdir", metavar="OUTDIR", help="output folder of `sartor fit`")
    parser.add_argument(
        "--output", "-o", metavar="FILE.png",
        help="where to write the figure (default: OUTDIR/fit.png)",
    )
    parser.add_argument(
        "--max-points", type=int, default=5000, metavar="N",
        help="most measured samples drawn per top panel (default: 5000)",
    )
    parser.add_argument(
        "--no-estimate", action="store_true",
        help="do not draw the thesis §5.2.2 step-by-step estimate (dashed) under the fit",
    )
    parser.add_argument("--title", help="figure title (default: from the input file name)")
    args = parser.parse_args(argv)
    if args.max_points < 10:
        parser.error("--max-points must be at least 10")

    try:
        fit, data, csv_path = read_fit(args.outdir)
        output = args.output or os.path.join(args.outdir, "fit.png")
        fig = make_figure(fit, data, csv_path, args.max_points, args.title, args.no_estimate)
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
