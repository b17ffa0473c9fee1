#!/usr/bin/env bash
# The Cusick drape test as shipped (cases/contact/cusick_cotton_twill.yaml: the
# static minimiser, 18 rings): a certified equilibrium; the two discs' reactions
# (each about 14 kN of squeeze) add up to the specimen's weight; the overhang
# hangs below the support; and the drape coefficient in summary.json matches
# the test's own one, from final.obj's triangles projected on a grid. Then on
# 12 rings, whose rim vertices just outside the discs are pressed by both
# discs' rims through their edges' samples: certified, Coulomb checked against
# each disc's cone (every vertex between the discs counts against both).
#   cusick_static.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
sartor=$1 cases=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$cases/cusick_cotton_twill.yaml" --no-plot --output "$work/cusick" > "$work/cusick.log"
tail -1 "$work/cusick.log"
/usr/bin/python3 - "$work/cusick" <<'PY'
import json, math, sys
import numpy as np
out = sys.argv[1]
s = json.load(open(f"{out}/summary.json"))
failures = []
if s["certificate"]["verdict"] != "certified":
    failures.append(f"certificate: {s['certificate']['verdict']}")
radius, support, density, g = 0.15, 0.09, 0.25, 9.80665
# The specimen's area as meshed (its outline is a polygon through the circle).
material = s["contact"]["drape"]["specimen_area_m2"]
if not 0.99 * math.pi * radius**2 < material <= math.pi * radius**2:
    failures.append(f"specimen area {material} m^2")
weight = density * material * g
lift = sum(b["reaction_N"][2] for b in s["contact"]["bodies"])
# 1e-5 of the weight: far above the solve's residual (1e-9 of it) and the
# round-off of two 14 kN reactions cancelling.
if abs(lift - weight) > 1e-5 * weight:
    failures.append(f"the discs carry {lift} N for a weight of {weight} N")
vertices = np.array([list(map(float, l.split()[1:4])) for l in open(f"{out}/final.obj")
                     if l.startswith("v ")])
faces = np.array([[int(t.split("/")[0]) - 1 for t in l.split()[1:4]]
                  for l in open(f"{out}/final.obj") if l.startswith("f ")])
if not vertices[:, 2].min() < -0.02:
    failures.append(f"the overhang does not hang: lowest point {vertices[:, 2].min()} m")
# The shadow: grid cells whose centre lies in some projected triangle.
n = 1200
side = 2 * radius * 1.02
centres = (np.arange(n) + 0.5) / n * side - side / 2
X, Y = np.meshgrid(centres, centres)
covered = np.zeros_like(X, dtype=bool)
for a, b, c in vertices[faces][:, :, :2]:
    lo, hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)
    i0, i1 = np.searchsorted(centres, [lo[1], hi[1]])
    j0, j1 = np.searchsorted(centres, [lo[0], hi[0]])
    px, py = X[i0:i1, j0:j1], Y[i0:i1, j0:j1]
    det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
    if det == 0.0:
        continue
    u = ((px - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (py - a[1])) / det
    v = ((b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])) / det
    covered[i0:i1, j0:j1] |= (u >= 0) & (v >= 0) & (u + v <= 1)
shadow = covered.sum() * (side / n) ** 2
disc = math.pi * support**2
mine = (shadow - disc) / (material - disc)
theirs = s["contact"]["drape"]["coefficient"]
print(f"drape coefficient {theirs:.4f} (summary.json), {mine:.4f} (this test's grid); "
      f"discs carry {lift:.6f} N of {weight:.6f} N")
if not 0.0 < theirs < 1.0 or abs(mine - theirs) > 5e-3:
    failures.append(f"drape coefficient {theirs} against the test's {mine}")
# The nodes: maxima of the rim's projected radius round the flat specimen's
# polar angle, rising and falling by 1 % of its radius (docs/contact.md).
import h5py
with h5py.File(f"{out}/result.h5", "r") as f:
    flat = f["/mesh/initial_position"][:]
flat_r = np.hypot(flat[:, 0], flat[:, 1])
rim = np.where(flat_r > 0.99 * flat_r.max())[0]
rim = rim[np.argsort(np.arctan2(flat[rim, 1], flat[rim, 0]))]
drawn = np.hypot(vertices[rim, 0], vertices[rim, 1])
prominence = 0.01 * radius
start = int(np.argmin(drawn))
rising, top, bottom, nodes = True, drawn[start], drawn[start], 0
for r in np.roll(drawn, -start)[1:].tolist() + [drawn[start]]:
    if rising:
        top = max(top, r)
        if top - r >= prominence:
            nodes, rising, bottom = nodes + 1, False, r
    else:
        bottom = min(bottom, r)
        if r - bottom >= prominence:
            rising, top = True, r
print(f"nodes {s['contact']['drape']['nodes']} (summary.json), {nodes} (this test's)")
if s["contact"]["drape"]["nodes"] != nodes or not 4 <= nodes <= 12:
    failures.append(f"nodes {s['contact']['drape']['nodes']} against the test's {nodes}")
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
"$sartor" run "$cases/cusick_cotton_twill.yaml" --mesh-rings 12 --no-plot \
  --output "$work/cusick12" > "$work/cusick12.log"
tail -1 "$work/cusick12.log"
/usr/bin/python3 - "$work/cusick12" <<'PY'
import json, sys
import numpy as np
out = sys.argv[1]
s = json.load(open(f"{out}/summary.json"))
coulomb = s["certificate"]["coulomb"]
vertices = np.array([list(map(float, l.split()[1:4])) for l in open(f"{out}/final.obj")
                     if l.startswith("v ")])
# Between the discs (radius 0.09 m, 1.5 mm apart): each presses on the vertex.
clamped = int(np.sum(np.hypot(vertices[:, 0], vertices[:, 1]) < 0.09))
print(f"12 rings: {s['certificate']['verdict']}; {coulomb['contacts']} contacts, "
      f"{clamped} vertices between the discs, worst ratio {coulomb['worst_ratio']:.4f}")
failures = []
if s["certificate"]["verdict"] != "certified":
    failures.append(f"12 rings: certificate: {s['certificate']['verdict']}")
if coulomb["contacts"] < 2 * clamped:
    failures.append(f"12 rings: {coulomb['contacts']} contacts for {clamped} clamped vertices")
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
