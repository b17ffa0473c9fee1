#!/bin/bash
# Named design parameters (docs/sensitivity.md#named-parameters): the coarse
# skirt with four waist darts is draped, then edited by its parameters:
#  1. the front right dart slid 2 cm (DART.slide): exactly its three corners
#     move, each by 2 cm along the line from its first base to its second;
#  2. the front left dart opened 1 cm and deepened 2 cm (DART.open,
#     DART.depth): its bases move apart by 5 mm each along that line, its
#     apex 2 cm away from the bases' midpoint;
#  3. the pattern's sloper parameter skirt_length by 2 cm: both hems 2 cm
#     lower in the pattern, and the re-solved skirt's lowest point 1 to 3 cm
#     lower (the skirt hangs from the waist);
#  4. the back hem moved by a pointer through Psi = e e^T (SC §6), e along
#     x: its corners move by the pointer's x only;
#  5. a curve edit, the front right side's second control point 2 cm out:
#     every point of that Bezier moves by 3 t^2 (1 - t) of it (t found here
#     on the original curve), no corner moves, and its side seam's front
#     side gets longer in the rest mesh while the back side stays;
#  6. a drag of the front hem 1 cm down on the parameter skirt_length:
#     dg = s . dd / |s|^2 (SC §4.1), reported under the parameter's name.
# Every re-solve is certified. The expected corner moves are computed here
# from the pattern file. Then, resuming the drape directory: the rest mesh
# of a 3 cm dart slide Delaunay-smoothed, and an edit that folds the pattern
# (a dart slid 20 cm, past its neighbours) refused.
# Usage: edit_parameters.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
pattern="$root/cases/patterns/skirt_darts.json"
cat > "$out/edits.yaml" <<'YAML'
steps:
  - name: front right dart slid 2 cm
    change: {sf_dart_r.slide: 0.02}
  - name: front left dart 1 cm wider, 2 cm deeper
    change: {sf_dart_l.open: 0.01, sf_dart_l.depth: 0.02}
  - name: skirt 2 cm longer
    change: {skirt_length: 0.02}
  - name: back hem shadows the pointer along x
    pointer: [0.01, 0.005]
    moves:
      - {line: sb_hem, along: [2, 0]}
  - name: front right side bowed out
    moves:
      - {line: sf_side_r, control: 2, by: [0.02, 0]}
YAML
"$sartor" edit "$pattern" "$out/edits.yaml" -options_file_yaml \
  "$root/cases/garments/skirt_coarse.yaml" --no-plot --no-edit-outputs --output "$out/edit" \
  > "$out/edit.log" 2>&1 || { cat "$out/edit.log"; exit 1; }
/usr/bin/python3 - "$out" "$pattern" <<'PY'
import json, math, sys
out, pattern_file = sys.argv[1], sys.argv[2]
pattern = json.load(open(pattern_file))
front = next(p for p in pattern["panels"] if p["id"] == "skirt_front")
line = {l["id"]: l["points"] for l in front["outline"]}
# The corners: every outline line's start (points along a line follow its
# two corners by arc length, and are not checked here).
corners = {(p["id"], tuple(l["points"][0])) for p in pattern["panels"] for l in p["outline"]}
def unit(v):
    n = math.hypot(*v)
    return [v[0] / n, v[1] / n]
def dart(name):  # first base, apex, second base
    return line[name + "_in"][0], line[name + "_in"][-1], line[name + "_out"][-1]
failures = []
original = {p["id"]: p["before"]
            for p in json.load(open(f"{out}/edit/edit_01/outlines.json"))["panels"]}
def expect_moves(step, expected):
    """expected: {(panel, corner in pattern coordinates before any edit): its total move}.
    outlines.json lays the panels out on a sheet (a translation per panel): the
    first outline point, the hem's left corner at (0, 0), gives it."""
    outlines = json.load(open(f"{out}/edit/edit_0{step}/outlines.json"))
    checked = 0
    for panel in outlines["panels"]:
        points = original[panel["id"]]
        origin = points[0]
        for b, a in zip(points, panel["after"]):
            corner = (panel["id"], (b[0] - origin[0], b[1] - origin[1]))
            if not any(id == corner[0] and math.dist(c, corner[1]) < 1e-9 for id, c in corners):
                continue
            want = next((move for (id, c), move in expected.items()
                         if id == corner[0] and math.dist(c, corner[1]) < 1e-9), [0.0, 0.0])
            move = [a[0] - b[0], a[1] - b[1]]
            checked += 1
            if math.dist(move, want) > 1e-12:
                failures.append(f"edit {step}: {corner} moved {move}, expected {want}")
    if checked != len(corners):
        failures.append(f"edit {step}: {checked} of the {len(corners)} corners found")
b1, apex, b2 = dart("sf_dart_r")
e = unit([b2[0] - b1[0], b2[1] - b1[1]])
slide = [0.02 * e[0], 0.02 * e[1]]
step1 = {("skirt_front", tuple(c)): slide for c in (b1, apex, b2)}
expect_moves(1, step1)
l1, lapex, l2 = dart("sf_dart_l")
el = unit([l2[0] - l1[0], l2[1] - l1[1]])
axis = unit([lapex[0] - (l1[0] + l2[0]) / 2, lapex[1] - (l1[1] + l2[1]) / 2])
step2 = dict(step1)
step2[("skirt_front", tuple(l1))] = [-0.005 * el[0], -0.005 * el[1]]
step2[("skirt_front", tuple(l2))] = [0.005 * el[0], 0.005 * el[1]]
step2[("skirt_front", tuple(lapex))] = [0.02 * axis[0], 0.02 * axis[1]]
expect_moves(2, step2)
step3 = dict(step2)
for panel in ("skirt_front", "skirt_back"):
    for corner in ((0.0, 0.0), (0.6, 0.0)):
        step3[(panel, corner)] = [0.0, -0.02]
expect_moves(3, step3)
step4 = dict(step3)
for corner in ((0.0, 0.0), (0.6, 0.0)):
    step4[("skirt_back", corner)] = [0.01, -0.02]
expect_moves(4, step4)
expect_moves(5, step4)
side = line["sf_side_r"]
def bezier(t):
    b = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3]
    return [sum(w * p[c] for w, p in zip(b, side)) for c in (0, 1)]
def parameter_of(point):  # t on the original side line nearest `point`
    best = min((math.dist(bezier(k / 2000), point), k / 2000) for k in range(2001))[1]
    lo, hi = max(0.0, best - 1e-3), min(1.0, best + 1e-3)
    for _ in range(100):
        a, b = lo + (hi - lo) / 3, hi - (hi - lo) / 3
        if math.dist(bezier(a), point) < math.dist(bezier(b), point):
            hi = b
        else:
            lo = a
    return 0.5 * (lo + hi), math.dist(bezier(0.5 * (lo + hi)), point)
fifth = next(p for p in json.load(open(f"{out}/edit/edit_05/outlines.json"))["panels"]
             if p["id"] == "skirt_front")
fourth = next(p for p in json.load(open(f"{out}/edit/edit_04/outlines.json"))["panels"]
              if p["id"] == "skirt_front")
origin = original["skirt_front"][0]
on_side = 0
for b, a, o in zip(fourth["after"], fifth["after"], original["skirt_front"]):
    t, off = parameter_of([o[0] - origin[0], o[1] - origin[1]])
    if off > 1e-9 or not 1e-6 < t < 1 - 1e-6:
        continue  # not on the side line, or its corner
    on_side += 1
    want = [0.02 * 3 * t * t * (1 - t), 0.0]
    if math.dist([a[0] - b[0], a[1] - b[1]], want) > 1e-9:
        failures.append(f"edit 5: side point at t = {t} moved {[a[0] - b[0], a[1] - b[1]]}, "
                        f"expected {want}")
if on_side != 15:
    failures.append(f"edit 5: {on_side} inner points found on the side line, expected 15")
summary = json.load(open(f"{out}/edit/summary.json"))["edit"]["steps"]
before_seam, after_seam = (next(s for s in summary[k]["seam_rest_lengths"]
                                if "sf_side_r" in s["seam"]) for k in (3, 4))
grown = [after_seam[k] - before_seam[k] for k in ("a_m", "b_m")]
if not (max(grown) > 1e-4 and abs(min(grown)) <= 1e-12):
    failures.append(f"edit 5: the side seam's rest lengths changed by {grown} m: one side "
                    "should grow, the other stay")
for k, step in enumerate(summary, 1):
    if not (step["resolve"]["converged"] and step["resolve"]["certificate"] == "certified"):
        failures.append(f"edit {k}: re-solve {step['resolve']}")
if [c["parameter"] for c in summary[1]["changes"]] != ["sf_dart_l.open", "sf_dart_l.depth"]:
    failures.append(f"edit 2 changes {summary[1]['changes']}")
drop = summary[2]["lowest_point_z_m"]["before"] - summary[2]["lowest_point_z_m"]["resolved"]
if not 0.01 <= drop <= 0.03:
    failures.append(f"skirt_length 2 cm: lowest point lower by {drop} m, expected 1 to 3 cm")
if not abs(summary[2]["largest_corner_move_m"] - 0.02) <= 1e-12:
    failures.append(f"skirt_length 2 cm: corners moved {summary[2]['largest_corner_move_m']} m")
print(f"skirt_length 2 cm: lowest point {1e3 * drop:.1f} mm lower")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
# A drag on the sloper parameter, from the drape's directory.
/usr/bin/python3 - "$out" <<'PY'
import sys
out = sys.argv[1]
vertices = [list(map(float, line.split()[1:4]))
            for line in open(f"{out}/edit/final.obj") if line.startswith("v ")]
front = min((v for v in vertices if abs(v[0]) < 0.06 and v[1] < 0), key=lambda v: v[2])
with open(f"{out}/drag.yaml", "w") as stream:
    stream.write(f"""steps:
  - name: front hem dragged 1 cm down
    drag: {{point: [{front[0]!r}, {front[1]!r}, {front[2]!r}], by: [0, 0, -0.01]}}
    parameters: [skirt_length]
""")
PY
"$sartor" edit "$out/edit" "$out/drag.yaml" --no-edit-outputs --output "$out/drag" \
  > "$out/drag.log" 2>&1 || { cat "$out/drag.log"; exit 1; }
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
step = json.load(open(f"{out}/drag/summary.json"))["edit"]["steps"][0]
drag = step["drag"]["drags"][0]
parameter = step["drag"]["parameters"][0]
s, by = drag["sensitivity_m_per_unit"][0], drag["by_m"]
dot = lambda a, b: sum(x * y for x, y in zip(a, b))
expected = dot(s, by) / dot(s, s)
failures = []
if parameter["name"] != "skirt_length":
    failures.append(f"the drag's parameter is {parameter['name']}")
if not abs(parameter["change"] - expected) <= 1e-12 * abs(expected):
    failures.append(f"dg {parameter['change']}, s.dd/|s|^2 = {expected}")
if not step["resolve"]["certificate"] == "certified":
    failures.append(f"re-solve {step['resolve']}")
print(f"drag on skirt_length: dg {parameter['change']:.4f} m")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
# Delaunay smoothing of the edited rest mesh (SC §6), asked for at a
# quality the 3 cm slide of the front right dart falls below: edges are
# flipped, the vertices kept, and the re-solve on the flipped mesh is
# certified.
printf 'steps:\n  - name: slide\n    change: {sf_dart_r.slide: 0.03}\n' > "$out/smooth.yaml"
"$sartor" edit "$out/edit" "$out/smooth.yaml" --no-edit-outputs --edit-smoothing-quality 0.6 \
  --output "$out/smooth" > "$out/smooth.log" 2>&1 || { cat "$out/smooth.log"; exit 1; }
/usr/bin/python3 - "$out" <<'PY'
import json, sys
step = json.load(open(f"{sys.argv[1]}/smooth/summary.json"))["edit"]["steps"][0]
mesh = step["rest_mesh"]
print(f"smoothing: {mesh}")
if not (mesh["smoothed"] and mesh["flips"] > 0 and mesh["worst_quality_before_smoothing"] < 0.6):
    sys.exit(f"the 3 cm slide's rest mesh was not smoothed: {mesh}")
if step["resolve"]["certificate"] != "certified":
    sys.exit(f"re-solve on the smoothed mesh: {step['resolve']}")
PY
# An edit that folds the pattern over itself is refused.
printf 'steps:\n  - name: too far\n    change: {sf_dart_r.slide: 0.2}\n' > "$out/fold.yaml"
status=0
"$sartor" edit "$out/edit" "$out/fold.yaml" --no-edit-outputs --output "$out/fold" \
  > "$out/fold.log" 2>&1 || status=$?
if [ "$status" != 2 ] || ! grep -q "the edited pattern folds over itself.*panel 'skirt_front'" \
    "$out/fold.log"; then
  echo "a folding edit: exit status $status" >&2
  cat "$out/fold.log" >&2
  exit 1
fi
echo "a folding edit is refused"
