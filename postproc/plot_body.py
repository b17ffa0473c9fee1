#!/usr/bin/python3
"""Draw the body written by `sartor body`, with its skeleton.

Reads OUTDIR/body.obj (v and f lines) and, when present, OUTDIR/skeleton.json,
and writes OUTDIR/body.png (150 dpi): the body seen from the front (from -y)
and from its left side (from +x), flat-shaded, triangles drawn back to front;
over it the skeleton's bones as lines from joint to joint and, dashed, the
outline of each bone's radius profile (the cone garment placement wraps
around). The title gives the height and the triangle count.

Needs only numpy and matplotlib; run it with /usr/bin/python3.
"""

import argparse
import os
import sys

from sartor_plotio import PlotError, read_json, save_figure

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection


def read_obj(path):
    """Vertices and triangles (0-based) of an OBJ with v and f lines."""
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    vertices, faces = [], []
    with open(path, encoding="utf-8") as stream:
        for number, line in enumerate(stream, start=1):
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            try:
                if words[0] == "v":
                    vertices.append([float(w) for w in words[1:4]])
                elif words[0] == "f":
                    corners = [int(w.split("/")[0]) for w in words[1:]]
                    corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
                    for k in range(1, len(corners) - 1):
                        faces.append([corners[0], corners[k], corners[k + 1]])
            except ValueError:
                raise PlotError("%s:%d: not a number in: %s" % (path, number, line.strip()))
    if not faces:
        raise PlotError("%s: no faces" % path)
    return np.array(vertices), np.array(faces)


def draw_view(axes, vertices, faces, right, depth, title):
    """Flat-shaded projection onto (right, z), painter's order along `depth`."""
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    toward_viewer = -np.asarray(depth, dtype=float)
    visible = normals @ toward_viewer > 0.0
    light = toward_viewer + np.array([0.3, 0.3, 0.6])
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.6 * np.clip(normals @ light, 0.0, 1.0)
    order = np.argsort(-(corners.mean(axis=1) @ np.asarray(depth, dtype=float)))
    order = order[visible[order]]
    polygons = np.stack([corners[order] @ np.asarray(right, dtype=float), corners[order][:, :, 2]], axis=2)
    colours = np.outer(shade[order], [0.93, 0.82, 0.72])
    # Edges in the face colour hide the hairline gaps between neighbouring polygons.
    axes.add_collection(PolyCollection(polygons, facecolors=colours, edgecolors=colours, linewidths=0.3))
    axes.set_title(title)
    axes.set_aspect("equal")
    horizontal = vertices @ np.asarray(right, dtype=float)
    axes.set_xlim(horizontal.min() - 0.05, horizontal.max() + 0.05)
    axes.set_ylim(vertices[:, 2].min() - 0.03, vertices[:, 2].max() + 0.05)
    axes.set_xlabel("m")
    axes.set_ylabel("z (m)")


def draw_skeleton(axes, bones, right):
    right = np.asarray(right, dtype=float)
    for bone in bones:
        start, end = np.array(bone["start"]), np.array(bone["end"])
        axes.plot([start @ right, end @ right], [start[2], end[2]], color="tab:blue", lw=1.5)
        axes.plot([start @ right], [start[2]], "o", color="tab:red", ms=2.5)
        axes.plot([end @ right], [end[2]], "o", color="tab:red", ms=2.5)
        # Radius profile: the cone's silhouette in this view.
        along = np.array([end @ right - start @ right, end[2] - start[2]])
        length = np.linalg.norm(along)
        if length == 0.0:
            continue
        across = np.array([-along[1], along[0]]) / length
        for side in (-1.0, 1.0):
            a = np.array([start @ right, start[2]]) + side * bone["start_radius"] * across
            b = np.array([end @ right, end[2]]) + side * bone["end_radius"] * across
            axes.plot([a[0], b[0]], [a[1], b[1]], color="tab:blue", lw=0.6, ls="--", alpha=0.7)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir", help="output folder of `sartor body`")
    parser.add_argument("--output", help="PNG file to write (default OUTDIR/body.png)")
    parser.add_argument("--no-skeleton", action="store_true", help="draw the body only")
    args = parser.parse_args()
    try:
        vertices, faces = read_obj(os.path.join(args.outdir, "body.obj"))
        skeleton_path = os.path.join(args.outdir, "skeleton.json")
        bones = []
        if not args.no_skeleton and os.path.isfile(skeleton_path):
            bones = read_json(skeleton_path).get("bones", [])
        figure, (front, side) = plt.subplots(1, 2, figsize=(10, 8))
        height = np.ptp(vertices[faces].reshape(-1, 3)[:, 2])
        figure.suptitle("body: %d triangles, height %.3f m" % (len(faces), height))
        draw_view(front, vertices, faces, [1, 0, 0], [0, 1, 0], "front (from -y; x right)")
        draw_view(side, vertices, faces, [0, -1, 0], [-1, 0, 0], "left side (from +x; -y right)")
        for axes, right in ((front, [1, 0, 0]), (side, [0, -1, 0])):
            draw_skeleton(axes, bones, right)
        output = args.output or os.path.join(args.outdir, "body.png")
        save_figure(figure, output, 150)
    except PlotError as error:
        sys.exit("plot_body.py: error: %s" % error)


if __name__ == "__main__":
    main()
