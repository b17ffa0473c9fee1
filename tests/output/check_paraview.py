#!/usr/bin/python3
"""Opens every XDMF and OBJ output of sartor runs in ParaView (its Python
module, Debian's python3-paraview), as a user would, and checks what
ParaView shows: the arrays (node and cell fields, fabric and panel ids,
material uv, contact and seam loads of drapes, creep strains), the point
and cell counts of result.h5, the time steps of the series with the
geometry moving over them, and the OBJ groups. Every array ParaView shows
must carry its unit in the HDF5 file (this test's own table).

  check_paraview.py KIND:DIR [KIND:DIR ...]
KIND: run, creep, drape or contact (a static run with a body: its contact
loads). Fails (never skips) without ParaView.
"""
import glob
import os
import sys

import h5py
import numpy as np
import paraview.simple as pv

UNITS = {"position": "m", "displacement": "m", "material_uv": "m", "fabric_id": "1",
         "panel_id": "1", "strain_warp": "1", "strain_weft": "1", "strain_shear": "1",
         "tension_warp": "N/m", "tension_weft": "N/m", "viscoelastic_warp": "1",
         "permanent_warp": "1", "viscoelastic_weft": "1", "permanent_weft": "1",
         "contact_pressure": "Pa", "contact_normal_force": "N", "friction_force": "N",
         "friction_utilisation": "1", "seam_force": "N"}
CONTACT = {"contact_pressure", "contact_normal_force", "friction_force", "friction_utilisation"}
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def h5_units(path):
    """Units of every dataset of `path`, by its last name component."""
    units = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and "units" in obj.attrs:
                value = obj.attrs["units"]
                units[name.split("/")[-1]] = value.decode() if isinstance(value, bytes) else value
        f.visititems(visit)
        counts = (f["/mesh/initial_position"].shape[0], f["/mesh/triangles"].shape[0])
    return units, counts


def expected_arrays(kind, has_panels):
    nodes = {"displacement"}
    cells = {"strain_warp", "strain_weft", "strain_shear", "tension_warp", "tension_weft",
             "material_uv", "fabric_id"}
    if has_panels:
        cells.add("panel_id")
    if kind in ("drape", "contact"):
        nodes |= CONTACT
    if kind == "drape":
        nodes.add("seam_force")
    return nodes, cells


def check_xmf(path, kind, series):
    units, (vertices, triangles) = h5_units(path.replace(".xmf", ".h5"))
    reader = pv.Xdmf3ReaderS(FileName=[path])
    # A series shows its states at their times (as ParaView's time bar asks).
    times = list(reader.TimestepValues)
    if series and times:
        reader.UpdatePipeline(time=times[0])
    else:
        reader.UpdatePipeline()
    info = reader.GetDataInformation()
    check(info.GetNumberOfPoints() == vertices, f"{path}: {info.GetNumberOfPoints()} points")
    check(info.GetNumberOfCells() == triangles, f"{path}: {info.GetNumberOfCells()} cells")
    nodes, cells = set(reader.PointData.keys()), set(reader.CellData.keys())
    want_nodes, want_cells = expected_arrays(kind, "panel_id" in units)
    if series:
        want_nodes = (want_nodes - CONTACT - {"seam_force"}) | {"position"}
        if kind == "creep":
            want_cells |= {"viscoelastic_warp", "permanent_warp"}
    check(want_nodes <= nodes, f"{path}: node arrays {sorted(nodes)} lack {want_nodes - nodes}")
    check(want_cells <= cells, f"{path}: cell arrays {sorted(cells)} lack {want_cells - cells}")
    for name in nodes | cells:
        check(units.get(name) == UNITS.get(name, "?"),
              f"{path}: array {name} has units {units.get(name)!r} in the HDF5 file")
    if "panel_id" in cells:
        low, high = reader.CellData["panel_id"].GetRange()
        check(low == 0 and high >= 1, f"{path}: panel ids {low}..{high}")
    if series:
        check_time_steps(path, reader)


def check_time_steps(path, reader):
    times = list(reader.TimestepValues)
    check(len(times) >= 2, f"{path}: {len(times)} time steps")
    check(all(float(f"{t:.9g}") == t for t in times), f"{path}: noisy times {times}")
    bounds = []
    for t in (times[0], times[-1]):
        reader.UpdatePipeline(time=t)
        bounds.append(np.array(reader.GetDataInformation().GetBounds()))
    moved = np.abs(bounds[1] - bounds[0]).max()
    check(moved > 1e-4, f"{path}: the geometry does not move over the series ({moved} m)")


def check_obj(path):
    with open(path) as f:
        lines = f.read().splitlines()
    vertices = sum(1 for line in lines if line.startswith("v "))
    groups = len({line for line in lines if line.startswith("g ")})
    reader = pv.OpenDataFile(path)
    reader.UpdatePipeline()
    info = reader.GetDataInformation()
    check(info.GetNumberOfPoints() == vertices,
          f"{path}: ParaView reads {info.GetNumberOfPoints()} points of {vertices}")
    if groups > 1:
        low, high = reader.CellData["GroupIds"].GetRange()
        check(high - low + 1 == groups, f"{path}: {high - low + 1} groups of {groups}")


def check_directory(kind, directory):
    xmfs = sorted(glob.glob(os.path.join(directory, "*.xmf")))
    check(xmfs, f"{directory}: no XDMF file")
    for path in xmfs:
        check_xmf(path, kind, os.path.basename(path) == "series.xmf")
    for path in sorted(glob.glob(os.path.join(directory, "*.obj"))):
        check_obj(path)


for argument in sys.argv[1:]:
    kind, directory = argument.split(":", 1)
    check_directory(kind, directory)
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("check_paraview: every XDMF and OBJ file opened in ParaView", pv.GetParaViewVersion())
