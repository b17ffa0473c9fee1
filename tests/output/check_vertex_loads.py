#!/usr/bin/python3
"""The contact loads of a sheet resting on a frictionless plane
(sheet_on_plane.yaml): away from its pinned edge every vertex carries its
own weight, so the contact pressure is the areal weight rho g; the pinned
edge carries none; there is no friction.

  check_vertex_loads.py DIR
"""
import sys

import h5py
import numpy as np

DENSITY = 0.1       # kg/m^2, the case's
GRAVITY = 9.80665   # m/s^2
directory = sys.argv[1]
with h5py.File(f"{directory}/result.h5", "r") as f:
    pressure = f["/fields/contact_pressure"][:]
    friction = f["/fields/friction_force"][:]
    x = f["/mesh/initial_position"][:, 0]
areal_weight = DENSITY * GRAVITY
far = x > 0.25      # the edge's bending has decayed (many penalty lengths)
error = np.abs(pressure[far] / areal_weight - 1).max()
failures = []
if not error < 1e-4:
    failures.append(f"contact pressure off the areal weight by {error:.3g} (relative)")
if np.abs(pressure[x < 1e-3]).max() != 0:
    failures.append("pinned vertices carry contact pressure")
if np.abs(friction).max() != 0:
    failures.append("friction on a frictionless plane")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"check_vertex_loads: pressure = rho g within {error:.2g} on {far.sum()} vertices")
