#!/usr/bin/python3
"""Draw a garment wrapped by `sartor wrap` or dragged by `sartor drag`.

Reads OUTDIR/wrapped.obj and wrap.json (wrap) or OUTDIR/dragged.obj and
drag.json (drag), and OUTDIR/body_points.csv, and writes OUTDIR/wrap.png or
OUTDIR/drag.png (150 dpi): three views (front from -y, side from +x, top
from +z) of the body's surface samples (grey dots) and the garment's
triangles (flat-shaded, drawn back to front, half transparent). Wrap: each
body mark as a red line and the cloth's points on the cloth marks as blue
dots. Drag: each grabbed vertex's start (green) and end (red), and the pins
(black). The title gives the run's numbers.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_csv_columns, read_json, save_figure

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection

VIEWS = (("front (from -y)", [1, 0, 0], [0, 1, 0]),
         ("side (from +x)", [0, -1, 0], [-1, 0, 0]),
         ("top (from +z)", [1, 0, 0], [0, 0, -1]))


def read_obj(path):
    """Vertices and triangles (0-based) of an OBJ with v and f lines."""
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    vertices, faces = [], []
    with open(path, encoding="utf-8") as stream:
        for number, line in enumerate(stream, start=1):
            words = line.split("#", 1)[0].split()
            try:
                if words and words[0] == "v":
                    vertices.append([float(w) for w in words[1:4]])
                elif words and words[0] == "f":
                    corners = [int(w.split("/")[0]) - 1 for w in words[1:]]
                    for k in range(1, len(corners) - 1):
                        faces.append([corners[0], corners[k], corners[k + 1]])
            except ValueError:
                raise PlotError("%s:%d: not a number in: %s" % (path, number, line.strip()))
    if not faces:
        raise PlotError("%s: no faces" % path)
    return np.array(vertices), np.array(faces)


def view_axes(right, depth):
    """The (right, up) axes of a view along `depth`."""
    right, depth = np.asarray(right, float), np.asarray(depth, float)
    up = np.cross(right, depth)
    return right, -up if up @ [0, 0, 1] < 0 or (up @ [0, 0, 1] == 0 and up @ [0, 1, 0] < 0) else up


def draw_view(axes, vertices, faces, body, right, depth, title):
    right, up = view_axes(right, depth)
    depth = np.asarray(depth, float)
    if len(body):
        axes.scatter(body @ right, body @ up, s=0.5, color="0.7", zorder=0)
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    shade = 0.35 + 0.6 * np.abs(normals @ -depth)
    order = np.argsort(-(corners.mean(axis=1) @ depth))
    polygons = [np.column_stack((corners[t] @ right, corners[t] @ up)) for t in order]
    colours = [(0.2 * s, 0.45 * s, 0.8 * s, 0.6) for s in shade[order]]
    axes.add_collection(PolyCollection(polygons, facecolors=colours, edgecolors="k",
                                       linewidths=0.2, zorder=1))
    axes.set_title(title)
    axes.set_aspect("equal")
    axes.autoscale_view()
    return right, up


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="output folder of `sartor wrap` or `sartor drag`")
    args = parser.parse_args()
    try:
        wrapped = os.path.isfile(os.path.join(args.outdir, "wrap.json"))
        name = "wrap" if wrapped else "drag"
        summary = read_json(os.path.join(args.outdir, name + ".json"))
        vertices, faces = read_obj(os.path.join(args.outdir,
                                                "wrapped.obj" if wrapped else "dragged.obj"))
        columns = read_csv_columns(os.path.join(args.outdir, "body_points.csv"), ["x", "y", "z"])
        body = np.column_stack((columns["x"], columns["y"], columns["z"]))
        figure, panes = plt.subplots(1, 3, figsize=(15, 6))
        ratio = summary["edge_length_ratio"]
        if wrapped:
            mismatch = summary["mark_mismatch_m"]
            figure.suptitle("wrap: %d triangles; mark mismatch max %.1f mm (rms %.1f mm); closest "
                            "vertex %.1f mm above the body; edge / rest %.2f..%.2f; %.3f s CPU"
                            % (summary["mesh"]["triangles"], 1e3 * mismatch["max"],
                               1e3 * mismatch["rms"], 1e3 * summary["min_body_distance_m"],
                               ratio["min"], ratio["max"], summary["timing_s"]["wrap_cpu"]))
        else:
            figure.suptitle("drag: %d drags; closest vertex %.1f mm above the body; edge / rest "
                            "%.2f..%.2f; %.3f s CPU"
                            % (len(summary["drags"]), 1e3 * summary["min_body_distance_m"],
                               ratio["min"], ratio["max"], summary["timing_s"]["drag_cpu"]))
        for axes, (title, right, depth) in zip(panes, VIEWS):
            right, up = draw_view(axes, vertices, faces, body, right, depth, title)
            if wrapped:
                for pair in summary["mark_pairs"]:
                    line = np.array(pair["body"])
                    axes.plot(line @ right, line @ up, color="tab:red", lw=1.5, zorder=2)
                    if pair["cloth"]:
                        dots = np.array(pair["cloth"])
                        axes.scatter(dots @ right, dots @ up, s=6, color="tab:blue", zorder=3)
            else:
                for drag in summary["drags"]:
                    start, end = np.array(drag["start_m"]), np.array(drag["end_m"])
                    axes.scatter([start @ right], [start @ up], s=25, color="tab:green", zorder=3)
                    axes.scatter([end @ right], [end @ up], s=25, color="tab:red", zorder=3)
                    for pin in drag["pins"]:
                        p = vertices[pin]
                        axes.scatter([p @ right], [p @ up], s=25, color="k", marker="x", zorder=3)
        save_figure(figure, os.path.join(args.outdir, name + ".png"), 150)
    except (PlotError, KeyError) as error:
        sys.exit("plot_wrap.py: error: %s" % error)


if __name__ == "__main__":
    main()
