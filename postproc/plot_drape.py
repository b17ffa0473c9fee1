#!/usr/bin/python3
"""Draw the garment draped by `sartor drape` on the mannequin, coloured by strain.

Reads OUTDIR/result.h5 (the draped garment, its per-triangle strains and
tensions, its fabrics), OUTDIR/body.obj (the body) and OUTDIR/summary.json,
and writes OUTDIR/drape.png (150 dpi): the garment on the body seen from the
front (from -y), the left side (from +x) and the back (from +y), the garment
coloured by --field (default strain: the larger of |warp| and |weft| strain
per triangle, in %) with a colour bar, flat-shaded, body and garment
triangles drawn together back to front (painter's algorithm), a 10 cm scale
bar. The title gives the pattern, the fabrics, the triangle count, the
largest seam gap, the deepest penetration and the body's reaction against
the garment's weight.

Needs numpy, matplotlib and h5py; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure
from plot_body import read_obj
from sartor_render import FIELDS, add_scale_bar, draw_view, field_values, read_result

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib import cm, colors

# (right, up, toward the viewer) of each view; the mannequin faces -y.
VIEWS = [
    ("front (from -y)", ([1, 0, 0], [0, 0, 1], [0, -1, 0])),
    ("left side (from +x)", ([0, 1, 0], [0, 0, 1], [1, 0, 0])),
    ("back (from +y)", ([-1, 0, 0], [0, 0, 1], [0, 1, 0])),
]


def title_of(summary, fabrics):
    drape = summary.get("drape", {})
    mesh = summary.get("mesh", {})
    return "%s in %s: %s triangles, %s\nseam gap %.1e m, penetration %.1e m, reaction/weight - 1 = %.1e" % (
        os.path.basename(str(summary.get("pattern", "garment"))),
        ", ".join(fabrics or summary.get("fabrics", ["?"])),
        mesh.get("triangles", "?"),
        "converged" if drape.get("converged") else "NOT converged",
        drape.get("largest_seam_gap_m", float("nan")),
        drape.get("max_penetration_m", float("nan")),
        drape.get("relative_imbalance", float("nan")),
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="output folder of `sartor drape`")
    parser.add_argument("--output", help="PNG file to write (default OUTDIR/drape.png)")
    parser.add_argument("--dpi", type=float, default=150, help="resolution of the PNG (default 150)")
    parser.add_argument("--field", default="strain",
                        help="colour: %s, or a cell field of result.h5 (default strain)" % ", ".join(FIELDS))
    args = parser.parse_args()
    try:
        body = read_obj(os.path.join(args.outdir, "body.obj"))
        positions, triangles, cells, fabrics = read_result(os.path.join(args.outdir, "result.h5"))
        summary = read_json(os.path.join(args.outdir, "summary.json"))
        label, values = field_values(cells, args.field)
        norm = colors.Normalize(vmin=min(0.0, values.min()), vmax=max(values.max(), 1e-12))
        mapper = cm.ScalarMappable(norm=norm, cmap="viridis")
        figure, axes = plt.subplots(1, 3, figsize=(15, 7.5), constrained_layout=True)
        figure.suptitle(title_of(summary, fabrics))
        for ax, (title, view) in zip(axes, VIEWS):
            draw_view(ax, (positions, triangles), mapper.to_rgba(values), view, title, body, cloth_lift=0.04)
            ax.set_ylabel("z (m)")
        add_scale_bar(axes[0])
        figure.colorbar(mapper, ax=axes, shrink=0.7, label=label)
        save_figure(figure, args.output or os.path.join(args.outdir, "drape.png"), args.dpi)
    except PlotError as error:
        sys.exit("plot_drape.py: error: %s" % error)


if __name__ == "__main__":
    main()
