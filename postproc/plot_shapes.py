#!/usr/bin/python3
"""Draw the final shapes of several `sartor run` results side by side.

Reads RUN_DIR/final.obj of each run and writes one PNG (150 dpi): a 3D view
of every cloth, shaded by height (z), all panels on the same axes limits so
that their shapes compare at a glance (e.g. the residual bulge of the push
test for three creep moduli). Labels default to the folder names.

    postproc/plot_shapes.py out/push_E3000 out/push_E300 out/push_E30 \\
        --labels "E = 3000,E = 300,E = 30" --output out/push_shapes.png

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, save_figure
from plot_body import read_obj

import numpy as np
import matplotlib.pyplot as plt


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="RUN_DIR", help="sartor run output folders")
    parser.add_argument("--labels", help="comma-separated panel titles [the folder names]")
    parser.add_argument("--output", required=True, metavar="FILE.png", help="the picture")
    parser.add_argument("--view", default="25,-60", metavar="ELEV,AZIM",
                        help="view elevation and azimuth, degrees [25,-60]")
    arguments = parser.parse_args()
    try:
        labels = (arguments.labels.split(",") if arguments.labels
                  else [os.path.basename(os.path.normpath(r)) for r in arguments.runs])
        if len(labels) != len(arguments.runs):
            raise PlotError("--labels: %d labels for %d runs" % (len(labels), len(arguments.runs)))
        try:
            elevation, azimuth = (float(v) for v in arguments.view.split(","))
        except ValueError:
            raise PlotError("--view: expected ELEV,AZIM in degrees, got '%s'" % arguments.view)
        shapes = [read_obj(os.path.join(run, "final.obj")) for run in arguments.runs]
        points = np.vstack([v for v, _ in shapes])
        low, high = points.min(axis=0), points.max(axis=0)
        span = max(high - low)
        centre = 0.5 * (low + high)
        figure = plt.figure(figsize=(4.0 * len(shapes), 4.0))
        for k, ((vertices, faces), label) in enumerate(zip(shapes, labels)):
            axes = figure.add_subplot(1, len(shapes), k + 1, projection="3d")
            axes.plot_trisurf(vertices[:, 0], vertices[:, 1], vertices[:, 2], triangles=faces,
                              cmap="viridis", vmin=low[2], vmax=high[2], linewidth=0.1,
                              edgecolor=(0, 0, 0, 0.25))
            for setter, c in zip((axes.set_xlim, axes.set_ylim, axes.set_zlim), centre):
                setter(c - 0.5 * span, c + 0.5 * span)
            axes.set_box_aspect((1, 1, 1))
            axes.view_init(elev=elevation, azim=azimuth)
            axes.set_title("%s\nlowest z %.4g m, highest %.4g m"
                           % (label, vertices[:, 2].min(), vertices[:, 2].max()), fontsize=9)
            axes.tick_params(labelsize=6)
        figure.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.86, wspace=0.05)
        save_figure(figure, arguments.output, 150)
    except PlotError as error:
        sys.exit("plot_shapes.py: error: %s" % error)


if __name__ == "__main__":
    main()
