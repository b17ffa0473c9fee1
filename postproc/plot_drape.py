#!/usr/bin/python3
"""Draw the garment draped by `sartor drape` on the mannequin.

Reads OUTDIR/final.obj (the draped garment), OUTDIR/body.obj (the body) and
OUTDIR/summary.json, and writes OUTDIR/drape.png (150 dpi): the garment on
the body seen from the front (from -y) and from its left side (from +x),
flat-shaded, body and garment triangles drawn together back to front (the
garment in blue, both sides of it shaded). The title gives the pattern, the
triangle count, the largest seam gap, the deepest penetration and the body's
reaction against the garment's weight.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure
from plot_body import read_obj

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection

BODY_COLOUR = np.array([0.93, 0.82, 0.72])
GARMENT_COLOUR = np.array([0.35, 0.5, 0.8])


def shaded_polygons(vertices, faces, right, depth, colour, two_sided):
    """Projected polygons, their depths and colours; back faces dropped unless two-sided."""
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    toward_viewer = -np.asarray(depth, dtype=float)
    facing = normals @ toward_viewer
    if two_sided:
        normals = normals * np.where(facing < 0.0, -1.0, 1.0)[:, None]
        keep = np.ones(len(faces), dtype=bool)
    else:
        keep = facing > 0.0
    light = toward_viewer + np.array([0.3, 0.3, 0.6])
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.6 * np.clip(normals @ light, 0.0, 1.0)
    polygons = np.stack([corners @ np.asarray(right, dtype=float), corners[:, :, 2]], axis=2)
    distance = corners.mean(axis=1) @ np.asarray(depth, dtype=float)
    return polygons[keep], distance[keep], np.outer(shade, colour)[keep]


def draw_view(axes, body, garment, right, depth, title):
    parts = [
        shaded_polygons(body[0], body[1], right, depth, BODY_COLOUR, False),
        shaded_polygons(garment[0], garment[1], right, depth, GARMENT_COLOUR, True),
    ]
    # A garment lying on the body is within millimetres of it, and its large
    # triangles' centres are no guide to depth against the body's small ones:
    # sorted 4 cm nearer than it is (more than a coarse triangle sags into a
    # convex body between its vertices), the garment covers the body it lies on.
    parts[1] = (parts[1][0], parts[1][1] - 0.04, parts[1][2])
    polygons = np.concatenate([p[0] for p in parts])
    distance = np.concatenate([p[1] for p in parts])
    colours = np.concatenate([p[2] for p in parts])
    order = np.argsort(-distance)
    axes.add_collection(
        PolyCollection(polygons[order], facecolors=colours[order], edgecolors=colours[order], linewidths=0.3)
    )
    axes.set_title(title)
    axes.set_aspect("equal")
    everything = np.concatenate([body[0], garment[0]])
    horizontal = everything @ np.asarray(right, dtype=float)
    axes.set_xlim(horizontal.min() - 0.05, horizontal.max() + 0.05)
    axes.set_ylim(everything[:, 2].min() - 0.03, everything[:, 2].max() + 0.05)
    axes.set_xlabel("m")
    axes.set_ylabel("z (m)")


def title_of(summary):
    drape = summary.get("drape", {})
    mesh = summary.get("mesh", {})
    return "%s: %s triangles, %s\nseam gap %.1e m, penetration %.1e m, reaction/weight - 1 = %.1e" % (
        os.path.basename(str(summary.get("pattern", "garment"))),
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
    args = parser.parse_args()
    try:
        body = read_obj(os.path.join(args.outdir, "body.obj"))
        garment = read_obj(os.path.join(args.outdir, "final.obj"))
        summary = read_json(os.path.join(args.outdir, "summary.json"))
        figure, (front, side) = plt.subplots(1, 2, figsize=(10, 8))
        figure.suptitle(title_of(summary))
        draw_view(front, body, garment, [1, 0, 0], [0, 1, 0], "front (from -y; x right)")
        draw_view(side, body, garment, [0, -1, 0], [-1, 0, 0], "left side (from +x; -y right)")
        save_figure(figure, args.output or os.path.join(args.outdir, "drape.png"), 150)
    except PlotError as error:
        sys.exit("plot_drape.py: error: %s" % error)


if __name__ == "__main__":
    main()
