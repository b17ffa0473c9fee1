"""Depth-sorted (painter's algorithm) pictures of cloth results.

Shared by plot_drape.py and plot_result.py: reads a result.h5 (the mesh, the
final positions, the per-triangle fields and their names) and draws views of
it, the cloth coloured by a field and flat-shaded, any body behind or in
front of it drawn in the same back-to-front order, with a colour bar.
Needs numpy, matplotlib and h5py (Debian python3-h5py).
"""

import os

import numpy as np
from matplotlib.collections import PolyCollection

from sartor_plotio import PlotError

BODY_COLOUR = np.array([0.93, 0.82, 0.72])

# name: (label, function of the cell fields giving the colour values)
FIELDS = {
    "strain": ("strain, largest of |warp|, |weft| (%)",
               lambda c: 100.0 * np.maximum(np.abs(c["strain_warp"]), np.abs(c["strain_weft"]))),
    "tension": ("tension, largest of warp, weft (N/m)",
                lambda c: np.maximum(c["tension_warp"], c["tension_weft"])),
    "shear": ("shear strain (%)", lambda c: 100.0 * c["strain_shear"]),
}


def names_of(dataset):
    """The `names` attribute of an id dataset as a list of str ([] if none)."""
    names = dataset.attrs.get("names")
    if names is None:
        return []
    return [n.decode() if isinstance(n, bytes) else str(n) for n in np.atleast_1d(names)]


def read_result(path):
    """Positions, triangles, cell fields (dict) and fabric names of a result.h5."""
    try:
        import h5py
    except ImportError:
        raise PlotError("needs h5py (Debian: python3-h5py)")
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    try:
        with h5py.File(path, "r") as f:
            positions = f["/fields/position"][:]
            triangles = f["/mesh/triangles"][:]
            cells = {name: f["/cell_fields/" + name][:] for name in f["/cell_fields"]}
            fabrics = names_of(f["/mesh/fabric_id"]) if "/mesh/fabric_id" in f else []
    except (OSError, KeyError) as error:
        raise PlotError("%s: not a Sartor result file: %s" % (path, error))
    return positions, triangles, cells, fabrics


def field_values(cells, field):
    """(label, per-triangle values) of a FIELDS name or a cell field's name."""
    # A failed solve's last state may hold non-finite values: drawn as 0.
    if field in FIELDS:
        label, function = FIELDS[field]
        return label, np.nan_to_num(function(cells), nan=0.0, posinf=0.0, neginf=0.0)
    if field in cells:
        return field, np.nan_to_num(cells[field], nan=0.0, posinf=0.0, neginf=0.0)
    raise PlotError("unknown field %r: one of %s" % (field, ", ".join(list(FIELDS) + sorted(cells))))


def shaded(vertices, faces, view, colours, two_sided):
    """Projected polygons, depths and shaded colours of one mesh in one view.

    view = (right, up, toward the viewer), unit vectors; back faces dropped
    unless two-sided (cloth is seen from both sides).
    """
    right, up, toward = (np.asarray(v, dtype=float) for v in view)
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    facing = normals @ toward
    if two_sided:
        normals = normals * np.where(facing < 0.0, -1.0, 1.0)[:, None]
        keep = np.ones(len(faces), dtype=bool)
    else:
        keep = facing > 0.0
    light = toward + 0.3 * right + 0.6 * up
    light /= np.linalg.norm(light)
    shade = 0.45 + 0.55 * np.clip(normals @ light, 0.0, 1.0)
    polygons = np.stack([corners @ right, corners @ up], axis=2)
    nearness = corners.mean(axis=1) @ toward
    rgb = np.asarray(colours, dtype=float)[:, :3] * shade[:, None]
    return polygons[keep], nearness[keep], rgb[keep]


def draw_view(axes, cloth, colours, view, title, body=None, cloth_lift=0.0):
    """One view: the cloth (vertices, faces) in `colours` and the body, depth-sorted.

    cloth_lift (m) brings the cloth's triangles that much nearer in the sort:
    a garment lying on a body within millimetres of it, with triangles much
    larger than the body's, would otherwise sort partly behind the surface
    it covers.
    """
    parts = [shaded(cloth[0], cloth[1], view, colours, True)]
    parts[0] = (parts[0][0], parts[0][1] + cloth_lift, parts[0][2])
    if body is not None:
        parts.append(shaded(body[0], body[1], view, np.tile(BODY_COLOUR, (len(body[1]), 1)), False))
    polygons = np.concatenate([p[0] for p in parts])
    nearness = np.concatenate([p[1] for p in parts])
    rgb = np.concatenate([p[2] for p in parts])
    order = np.argsort(nearness)  # farthest first
    axes.add_collection(PolyCollection(polygons[order], facecolors=rgb[order], edgecolors=rgb[order],
                                       linewidths=0.3))
    everything = np.concatenate([cloth[0]] + ([body[0]] if body is not None else []))
    everything = everything[np.all(np.isfinite(everything), axis=1)]
    if len(everything) == 0:
        raise PlotError("no finite positions to draw")
    horizontal, vertical = everything @ np.asarray(view[0], float), everything @ np.asarray(view[1], float)
    margin = 0.05 * max(np.ptp(horizontal), np.ptp(vertical), 1e-3)
    axes.set_xlim(horizontal.min() - margin, horizontal.max() + margin)
    axes.set_ylim(vertical.min() - margin, vertical.max() + margin)
    axes.set_aspect("equal")
    axes.set_title(title)
    axes.set_xlabel("m")


def add_scale_bar(axes, length=0.1):
    """A `length` metre bar in the lower left corner of `axes`."""
    x0, x1 = axes.get_xlim()
    y0, y1 = axes.get_ylim()
    x, y = x0 + 0.05 * (x1 - x0), y0 + 0.04 * (y1 - y0)
    axes.plot([x, x + length], [y, y], color="black", linewidth=2)
    axes.text(x + length / 2, y + 0.01 * (y1 - y0), "%g cm" % (100 * length), ha="center", va="bottom")
