#!/usr/bin/python3
"""Draw each edit of `sartor edit`: the pattern before and after beside the re-solved drape.

Reads OUTDIR/summary.json (its edit.steps), OUTDIR/body.obj and, per edit,
OUTDIR/edit_NN/outlines.json (the panels' outlines before and after, laid
out as the pattern sheet) and OUTDIR/edit_NN/resolved/result.h5 (the
re-solved drape), and writes OUTDIR/edit_NN/edit.png (150 dpi): on the left
the pattern (grey: before the edit, red: after), then the re-solved drape
on the body from the front (from -y) and the left side (from +x), coloured
by each vertex's displacement from the drape before the edit (the unedited
drape, OUTDIR/result.h5, for the first; the edit before's re-solve for the
others), in mm, with a colour bar and a 10 cm scale bar. The title names
the edit, its re-solve's certificate, the lowest point's change and the
largest prediction errors. Edits without a re-solved drape on disk
(`--no-edit-outputs`) get the pattern alone.

Needs numpy, matplotlib and h5py; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure
from plot_body import read_obj
from sartor_render import add_scale_bar, draw_view, read_result

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib import cm, colors

VIEWS = [
    ("front (from -y)", ([1, 0, 0], [0, 0, 1], [0, -1, 0])),
    ("left side (from +x)", ([0, 1, 0], [0, 0, 1], [1, 0, 0])),
]


def draw_outlines(axes, outlines):
    """The panels' outlines before (grey) and after (red) the edit."""
    for panel in outlines["panels"]:
        for key, style in (("before", dict(color="0.6", linewidth=1.0)),
                           ("after", dict(color="#c00", linewidth=1.2))):
            points = np.asarray(panel[key], dtype=float)
            if len(points) == 0:
                continue
            closed = np.vstack([points, points[:1]])
            axes.plot(closed[:, 0], closed[:, 1], **style)
        centre = np.asarray(panel["after"], dtype=float).mean(axis=0)
        axes.text(centre[0], centre[1], panel["id"], ha="center", va="center", fontsize=7)
    axes.set_aspect("equal")
    axes.set_title("pattern (grey: before, red: after)")
    axes.set_xlabel("m")


def title_of(step):
    low = step["lowest_point_z_m"]
    errors = step["error_against_resolved"]
    parts = ["%s ('%s'): re-solve %s, %s" % (step["folder"], step["name"],
                                              "converged" if step["resolve"]["converged"] else "NOT converged",
                                              step["resolve"]["certificate"]),
             "lowest point %+.1f mm; largest prediction error, mm: %s" % (
                 1e3 * (low["resolved"] - low["before"]),
                 ", ".join("%s %.1f" % (kind, 1e3 * errors[kind]["max_m"]) for kind in sorted(errors)))]
    return "\n".join(parts)


def plot_step(outdir, step, before_path, body, dpi):
    folder = os.path.join(outdir, step["folder"])
    outlines = read_json(os.path.join(folder, "outlines.json"))
    resolved_path = os.path.join(folder, "resolved", "result.h5")
    with_drape = os.path.isfile(resolved_path) and os.path.isfile(before_path)
    figure, axes = plt.subplots(1, 3 if with_drape else 1, figsize=(16, 7) if with_drape else (7, 7),
                                constrained_layout=True, squeeze=False)
    axes = axes[0]
    figure.suptitle(title_of(step))
    draw_outlines(axes[0], outlines)
    if with_drape:
        positions, triangles, _, _ = read_result(resolved_path)
        before, before_triangles, _, _ = read_result(before_path)
        if before.shape != positions.shape or not np.array_equal(before_triangles, triangles):
            raise PlotError("%s and %s are not the same mesh" % (before_path, resolved_path))
        moved = 1e3 * np.linalg.norm(positions - before, axis=1)
        per_triangle = np.nan_to_num(moved[triangles].mean(axis=1), nan=0.0)
        mapper = cm.ScalarMappable(norm=colors.Normalize(vmin=0.0, vmax=max(per_triangle.max(), 1e-9)),
                                   cmap="viridis")
        for ax, (title, view) in zip(axes[1:], VIEWS):
            draw_view(ax, (positions, triangles), mapper.to_rgba(per_triangle), view, title, body,
                      cloth_lift=0.04)
            ax.set_ylabel("z (m)")
        add_scale_bar(axes[1])
        figure.colorbar(mapper, ax=list(axes[1:]), shrink=0.7, label="displacement by the edit (mm)")
    save_figure(figure, os.path.join(folder, "edit.png"), dpi)
    plt.close(figure)
    return resolved_path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="output folder of `sartor edit`")
    parser.add_argument("--dpi", type=float, default=150, help="resolution of the PNGs (default 150)")
    args = parser.parse_args()
    try:
        summary = read_json(os.path.join(args.outdir, "summary.json"))
        steps = summary.get("edit", {}).get("steps")
        if steps is None:
            raise PlotError("%s/summary.json: no edit.steps (not a `sartor edit` output)" % args.outdir)
        body = read_obj(os.path.join(args.outdir, "body.obj"))
        before = os.path.join(args.outdir, "result.h5")
        for step in steps:
            before = plot_step(args.outdir, step, before, body, args.dpi)
    except PlotError as error:
        sys.exit("plot_edit.py: error: %s" % error)


if __name__ == "__main__":
    main()
