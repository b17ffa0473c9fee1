#!/usr/bin/python3
"""Plot a creep-model validation written by `sartor validate`.

Reads OUTDIR/validate.json and OUTDIR/validate.csv and writes one PNG (150 dpi):

* top: the measured strain of the predicted test (grey dots) and the
  prediction from the other test's fit (line) with its confidence band;
* bottom: the prediction error (measured - predicted, % strain) against time,
  with the band (shaded) and the prediction interval (band and the fit's
  noise, dashed); the title gives the RMSE and the largest error.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure, time_unit

import numpy as np
import matplotlib.pyplot as plt

PROGRAM = "plot_validate.py"
DPI = 150
CSV_COLUMNS = ("time_s", "strain_measured", "strain_predicted", "band_low", "band_high",
               "interval_half_width", "error")


def read_validation(outdir):
    json_path = os.path.join(outdir, "validate.json")
    csv_path = os.path.join(outdir, "validate.csv")
    for path in (json_path, csv_path):
        if not os.path.isfile(path):
            raise PlotError("%s: no such file (is %s an output folder of `sartor validate`?)"
                            % (path, outdir))
    report = read_json(json_path)
    if not isinstance(report, dict) or not isinstance(report.get("prediction"), dict):
        raise PlotError("%s: no 'prediction' object" % json_path)
    return report, read_csv_columns(csv_path, CSV_COLUMNS)


def make_figure(report, data, title):
    prediction = report["prediction"]
    fit = report.get("fit") or {}
    confidence = float(report.get("confidence_level", 0.95))
    time = data["time_s"]
    scale, unit = time_unit(time[-1] - time[0])
    t = time / scale
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(11, 8), sharex=True, layout="constrained")
    if title is None:
        title = "Prediction of %s from the fit of %s" % (
            os.path.basename(str((prediction.get("input") or {}).get("file", "?"))),
            os.path.basename(str(((fit.get("input") or {}).get("file", "?")))))
    fig.suptitle(title)

    top.plot(t, 100 * data["strain_measured"], ".", ms=1.5, color="0.55", label="measured",
             rasterized=True)
    top.fill_between(t, 100 * data["band_low"], 100 * data["band_high"], color="tab:blue",
                     alpha=0.3, lw=0, label="%.4g%% confidence band" % (100 * confidence))
    top.plot(t, 100 * data["strain_predicted"], color="tab:blue", lw=1.2, label="predicted")
    top.set_ylabel("strain (%)")
    top.grid(True, alpha=0.3)
    top.legend(loc="best", fontsize="small", markerscale=6)

    error = 100 * data["error"]
    band = 100 * 0.5 * (data["band_high"] - data["band_low"])
    bottom.plot(t, error, ".", ms=1.5, color="tab:red", alpha=0.6, rasterized=True,
                label="measured − predicted")
    bottom.fill_between(t, -band, band, color="tab:blue", alpha=0.3, lw=0,
                        label="confidence band")
    interval = 100 * data["interval_half_width"]
    bottom.plot(t, interval, "--", color="0.3", lw=0.8, label="prediction interval")
    bottom.plot(t, -interval, "--", color="0.3", lw=0.8)
    bottom.axhline(0.0, color="black", lw=0.8)
    bottom.set_xlabel("time (%s)" % unit)
    bottom.set_ylabel("error (% strain)")
    bottom.set_title("RMSE %.3g, max |error| %.3g at %.4g s, %.1f%% of the samples inside the "
                     "prediction interval" % (
                         float(prediction.get("rmse", float("nan"))),
                         float(prediction.get("max_abs_error", float("nan"))),
                         float(prediction.get("time_of_max_abs_error_s", float("nan"))),
                         100 * float(prediction.get("fraction_within_prediction_interval",
                                                    float("nan")))),
                     loc="left", fontsize=10)
    bottom.grid(True, alpha=0.3)
    bottom.legend(loc="upper right", fontsize="small", markerscale=6)
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot a creep-model validation: the output folder of `sartor validate` "
        "(validate.json and validate.csv).",
        epilog="Run with /usr/bin/python3.",
    )
    parser.add_argument("outdir", metavar="OUTDIR", help="output folder of `sartor validate`")
    parser.add_argument("--output", "-o", metavar="FILE.png",
                        help="where to write the figure (default: OUTDIR/validate.png)")
    parser.add_argument("--title", help="figure title (default: from the file names)")
    args = parser.parse_args(argv)
    try:
        report, data = read_validation(args.outdir)
        output = args.output or os.path.join(args.outdir, "validate.png")
        fig = make_figure(report, data, args.title)
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
