#!/usr/bin/python3
"""Reads every output file of sartor runs with meshio and h5py, as a user's
script or ParaView would, and checks what they must carry: units on every
HDF5 dataset, fabric and panel ids with their names, material uv in the
XDMF, clean output times, the current geometry at every state of the time
series, OBJ files whose v and vt pair up and whose panels are groups.

  check_outputs.py KIND:DIR [KIND:DIR ...]
KIND: run (a dynamic run), creep (a creep run) or drape:FABRIC:PANEL,PANEL
(a drape; its fabric and panel names). Fails (never skips) without meshio
or h5py: reading the files with them is the point.
"""
import glob
import json
import os
import sys
import tempfile

import h5py
import meshio
import numpy as np

# The units a reader should find, by dataset name (this test's own table).
UNITS = {"position": "m", "displacement": "m", "initial_position": "m", "material_uv": "m",
         "strain_warp": "1", "strain_weft": "1", "strain_shear": "1",
         "tension_warp": "N/m", "tension_weft": "N/m", "time": "s", "triangles": "1",
         "fabric_id": "1", "panel_id": "1", "viscoelastic_warp": "1", "permanent_warp": "1",
         "viscoelastic_weft": "1", "permanent_weft": "1", "contact_pressure": "Pa",
         "contact_normal_force": "N", "friction_force": "N", "friction_utilisation": "1",
         "seam_force": "N"}
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def check_h5(path, fabrics, panels):
    with h5py.File(path, "r") as f:
        datasets = []
        f.visititems(lambda name, obj: datasets.append(name) if isinstance(obj, h5py.Dataset) else None)
        for name in datasets:
            units = f[name].attrs.get("units")
            check(units is not None, f"{path}:{name} has no units")
            expected = UNITS.get(name.split("/")[-1])
            check(expected is not None and units is not None and text(units) == expected,
                  f"{path}:{name} units {units!r}, expected {expected!r}")
        nt = f["/mesh/triangles"].shape[0]
        check(f["/mesh/material_uv"].shape == (nt, 6), f"{path}: material_uv shape")
        names = [text(n) for n in np.atleast_1d(f["/mesh/fabric_id"].attrs["names"])]
        check(names == fabrics, f"{path}: fabric names {names}, expected {fabrics}")
        check(set(f["/mesh/fabric_id"][:]) <= set(range(len(fabrics))), f"{path}: fabric ids")
        if panels:
            names = [text(n) for n in np.atleast_1d(f["/mesh/panel_id"].attrs["names"])]
            check(names == panels, f"{path}: panel names {names}, expected {panels}")
            ids = set(f["/mesh/panel_id"][:])
            check(ids == set(range(len(panels))), f"{path}: panel ids {ids}")
        else:
            check("/mesh/panel_id" not in f, f"{path}: panel ids without panels")
        return nt, f["/mesh/material_uv"][:], f["/mesh/triangles"][:]


def check_result_xmf(path, nt, panels, drape):
    mesh = meshio.read(path)
    check(sum(len(c.data) for c in mesh.cells) == nt, f"{path}: {len(mesh.cells)} cell blocks")
    fields = set(mesh.cell_data)
    wanted = {"strain_warp", "tension_warp", "material_uv", "fabric_id"} | ({"panel_id"} if panels else set())
    check(wanted <= fields, f"{path}: cell fields {sorted(fields)} lack {sorted(wanted - fields)}")
    check(mesh.cell_data["material_uv"][0].shape == (nt, 6), f"{path}: material_uv as read")
    check("displacement" in mesh.point_data, f"{path}: no displacement")
    if drape:
        loads = {"contact_pressure", "contact_normal_force", "friction_force",
                 "friction_utilisation", "seam_force"}
        check(loads <= set(mesh.point_data),
              f"{path}: node fields {sorted(mesh.point_data)} lack {sorted(loads - set(mesh.point_data))}")


def check_series(path, creep):
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        states = [reader.read_data(k) for k in range(reader.num_steps)]
    check(len(states) >= 2, f"{path}: {len(states)} states")
    times = [t for t, _, _ in states]
    # Output times are whole multiples of the interval: written cleanly, a
    # time reads back as its shortest decimal (no 0.09999999999999999).
    check(all(float(f"{t:.9g}") == t for t in times), f"{path}: noisy times {times}")
    check(all(b > a for a, b in zip(times, times[1:])), f"{path}: times not increasing {times}")
    first, last = states[0][1]["position"], states[-1][1]["position"]
    check(np.allclose(first, points), f"{path}: the first state's position is not the mesh's")
    moved = np.abs(last - first).max()
    check(moved > 1e-4, f"{path}: the geometry does not change over time (moved {moved} m)")
    # position = initial + displacement at every state.
    initial = first - states[0][1]["displacement"]
    for t, point_data, _ in states:
        gap = np.abs(point_data["position"] - point_data["displacement"] - initial).max()
        check(gap < 1e-9, f"{path}: position - displacement changes at t = {t}")
    if creep:
        fields = set(states[-1][2])
        wanted = {"strain_warp", "viscoelastic_warp", "permanent_warp",
                  "strain_weft", "viscoelastic_weft", "permanent_weft"}
        check(wanted <= fields, f"{path}: creep fields {sorted(fields)}")
        check(np.abs(states[-1][2]["viscoelastic_warp"][0]).max() > 0,
              f"{path}: no viscoelastic strain at the end")


def check_obj(path, uv, triangles, groups):
    mesh = meshio.read(path)
    vt = mesh.point_data.get("obj:vt")
    check(uv is None or vt is not None, f"{path}: no vt")
    check(vt is None or len(vt) == len(mesh.points), f"{path}: v and vt do not pair")
    if uv is not None and vt is not None:
        tri = np.concatenate([c.data for c in mesh.cells])
        check(np.array_equal(tri, triangles), f"{path}: triangles differ from result.h5")
        corner_uv = vt[tri][:, :, :2].reshape(len(tri), 6)
        check(np.abs(corner_uv - uv).max() < 1e-12, f"{path}: vt differs from result.h5 material uv")
    found = len(set(np.concatenate(mesh.cell_data["obj:group_ids"])))
    check(found == groups, f"{path}: {found} groups, expected {groups}")
    # Round trip: what meshio writes of it reads back the same.
    with tempfile.TemporaryDirectory() as folder:
        again = os.path.join(folder, "again.obj")
        meshio.write(again, mesh)
        back = meshio.read(again)
    check(np.array_equal(back.points, mesh.points), f"{path}: points change in a meshio round trip")
    check(np.array_equal(np.concatenate([c.data for c in back.cells]),
                         np.concatenate([c.data for c in mesh.cells])),
          f"{path}: triangles change in a meshio round trip")


def check_directory(kind, directory):
    kind, *rest = kind.split(":")
    fabrics = [rest[0]] if rest else ["cotton_twill"]
    panels = rest[1].split(",") if len(rest) > 1 else []
    files = sorted(os.listdir(directory))
    for name in ["result.h5", "result.xmf", "series.h5", "series.xmf", "final.obj", "summary.json"]:
        check(name in files, f"{directory}: no {name}")
    nt, uv, triangles = check_h5(os.path.join(directory, "result.h5"), fabrics, panels)
    check_h5(os.path.join(directory, "series.h5"), fabrics, panels)
    check_result_xmf(os.path.join(directory, "result.xmf"), nt, panels, kind == "drape")
    check_series(os.path.join(directory, "series.xmf"), kind == "creep")
    check_obj(os.path.join(directory, "final.obj"), uv, triangles, max(len(panels), 1))
    if kind == "drape":
        check_obj(os.path.join(directory, "garment.obj"), uv, triangles, len(panels))
        check_obj(os.path.join(directory, "body.obj"), None, None, 1)
    for name in glob.glob(os.path.join(directory, "*.json")):
        json.load(open(name))
    unread = [f for f in files if os.path.splitext(f)[1] not in
              {".h5", ".xmf", ".obj", ".json", ".csv", ".txt", ".svg", ".png"}]
    check(not unread, f"{directory}: files this test does not read: {unread}")


for argument in sys.argv[1:]:
    kind, directory = argument.rsplit(":", 1)
    check_directory(kind, directory)
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("check_outputs: every file read with meshio and h5py")
