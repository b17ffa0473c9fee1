#!/usr/bin/python3
"""Draw the cloth of a `sartor run` in its final state, coloured by strain.

Reads OUTDIR/result.h5 (final positions, per-triangle strains and tensions,
fabrics) and OUTDIR/summary.json, and writes OUTDIR/result.png (150 dpi): the
cloth seen along -y (x right, z up), along +x (y right, z up) and from above
(x right, y up), coloured by --field (default strain: the larger of |warp|
and |weft| strain per triangle, in %) with a colour bar, flat-shaded and
drawn back to front (painter's algorithm). The title gives the case, the
fabrics, the triangle count, whether it converged and the largest
displacement.

Needs numpy, matplotlib and h5py; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure
from sartor_render import FIELDS, draw_view, field_values, read_result

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib import cm, colors

# (right, up, toward the viewer) of each view.
VIEWS = [
    ("front (from -y)", ([1, 0, 0], [0, 0, 1], [0, -1, 0]), "z (m)"),
    ("side (from +x)", ([0, 1, 0], [0, 0, 1], [1, 0, 0]), "z (m)"),
    ("top (from +z)", ([1, 0, 0], [0, 1, 0], [0, 0, 1]), "y (m)"),
]


def title_of(summary, fabrics, triangles):
    return "%s in %s: %d triangles, %s, largest displacement %.3g m" % (
        os.path.basename(str(summary.get("case", "run"))),
        ", ".join(fabrics or ["?"]),
        triangles,
        "converged" if summary.get("converged") else "NOT converged",
        summary.get("max_displacement_m", float("nan")),
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="output folder of `sartor run`")
    parser.add_argument("--output", help="PNG file to write (default OUTDIR/result.png)")
    parser.add_argument("--dpi", type=float, default=150, help="resolution of the PNG (default 150)")
    parser.add_argument("--field", default="strain",
                        help="colour: %s, or a cell field of result.h5 (default strain)" % ", ".join(FIELDS))
    args = parser.parse_args()
    try:
        positions, triangles, cells, fabrics = read_result(os.path.join(args.outdir, "result.h5"))
        summary = read_json(os.path.join(args.outdir, "summary.json"))
        label, values = field_values(cells, args.field)
        norm = colors.Normalize(vmin=min(0.0, values.min()), vmax=max(values.max(), 1e-12))
        mapper = cm.ScalarMappable(norm=norm, cmap="viridis")
        figure, axes = plt.subplots(1, 3, figsize=(15, 5.5), constrained_layout=True)
        figure.suptitle(title_of(summary, fabrics, len(triangles)))
        for ax, (title, view, vertical) in zip(axes, VIEWS):
            draw_view(ax, (positions, triangles), mapper.to_rgba(values), view, title)
            ax.set_ylabel(vertical)
        figure.colorbar(mapper, ax=axes, shrink=0.8, label=label)
        save_figure(figure, args.output or os.path.join(args.outdir, "result.png"), args.dpi)
    except PlotError as error:
        sys.exit("plot_result.py: error: %s" % error)


if __name__ == "__main__":
    main()
