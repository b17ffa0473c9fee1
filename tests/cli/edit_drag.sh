#!/bin/bash
# Direct 3D editing (Sensitive Couture §4.1; docs/sensitivity.md#direct-3d-editing):
# the coarse skirt, draped without friction, has the front hem point
# dragged 1 cm down; the edit's moves (the hem 1 cm longer per unit) are the
# direction of one parameter g, and the edit must take
# dg = s . dd / |s|^2 of them (s: the point's sensitivity, which the
# summary reports). Without friction the drape's response is smooth, so
#  - dg is positive (a hem pulled down is a longer hem),
#  - the predicted move dg s is the projection of the drag on s,
#  - the re-solved point moves down by 50 to 150 % of the 1 cm asked for,
#    and the re-solved drape is certified.
# A second step drags the front and the back hem points with two
# parameters (the front hem, the back hem): dg must be the least-squares
# fit, S^T (S dg - dd) = 0, computed here from the reported S.
# Usage: edit_drag.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
"$sartor" drape "$root/cases/patterns/skirt.json" -options_file_yaml \
  "$root/cases/garments/skirt_coarse.yaml" --body "mannequin mu=0 name=mannequin" --no-plot \
  --output "$out/drape" > "$out/drape.log" 2>&1 || { cat "$out/drape.log"; exit 1; }
# The front hem's lowest vertex (the front panel faces -y).
/usr/bin/python3 - "$out" <<'PY'
import sys
out = sys.argv[1]
vertices = [list(map(float, line.split()[1:4]))
            for line in open(f"{out}/drape/final.obj") if line.startswith("v ")]
front = min((v for v in vertices if abs(v[0]) < 0.06 and v[1] < 0), key=lambda v: v[2])
back = min((v for v in vertices if abs(v[0]) < 0.06 and v[1] > 0), key=lambda v: v[2])
with open(f"{out}/drag.yaml", "w") as stream:
    stream.write(f"""steps:
  - name: front hem dragged 1 cm down
    drag: {{point: [{front[0]!r}, {front[1]!r}, {front[2]!r}], by: [0, 0, -0.01]}}
    moves:
      - {{line: sf_hem_l, by: [0, -0.01]}}
      - {{line: sf_hem_r, by: [0, -0.01]}}
      - {{line: sb_hem, by: [0, -0.01]}}
  - name: front down, back up
    drag:
      - {{point: [{front[0]!r}, {front[1]!r}, {front[2] - 0.01!r}], by: [0, 0, -0.005]}}
      - {{point: [{back[0]!r}, {back[1]!r}, {back[2]!r}], by: [0, 0, 0.005]}}
    parameters:
      - name: front hem
        moves:
          - {{line: sf_hem_l, by: [0, -0.01]}}
          - {{line: sf_hem_r, by: [0, -0.01]}}
      - name: back hem
        moves:
          - {{line: sb_hem, by: [0, -0.01]}}
""")
PY
"$sartor" edit "$out/drape" "$out/drag.yaml" --no-edit-outputs --output "$out/edit" \
  > "$out/edit.log" 2>&1 || { cat "$out/edit.log"; exit 1; }
grep -q "drag: vertex" "$out/edit.log" || { cat "$out/edit.log"; exit 1; }
/usr/bin/python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
steps = json.load(open(f"{out}/edit/summary.json"))["edit"]["steps"]
step = steps[0]
drag = step["drag"]["drags"][0]
s, by = drag["sensitivity_m_per_unit"][0], drag["by_m"]
dg = step["drag"]["parameters"][0]["change"]
dot = lambda a, b: sum(x * y for x, y in zip(a, b))
failures = []
expected = dot(s, by) / dot(s, s)
if not abs(dg - expected) <= 1e-12 * abs(expected):
    failures.append(f"dg {dg}, s.dd/|s|^2 = {expected}")
if not dg > 0:
    failures.append(f"dg {dg}: a hem dragged down should lengthen")
predicted = drag["predicted_move_m"]
if not all(abs(p - dg * si) <= 1e-12 + 1e-9 * abs(dg * si) for p, si in zip(predicted, s)):
    failures.append(f"predicted move {predicted} is not dg s")
# The projection of the drag on s: its length |s.dd| / |s|.
if not abs(math.sqrt(dot(predicted, predicted)) - abs(dot(s, by)) / math.sqrt(dot(s, s))) <= 1e-12:
    failures.append("the predicted move is not the drag's projection on s")
if not abs(step["largest_corner_move_m"] - 0.01 * dg) <= 1e-12:
    failures.append(f"corner moves {step['largest_corner_move_m']} m, dg x 1 cm = {0.01 * dg}")
if not drag["point_distance_m"] <= 1e-9:
    failures.append(f"the dragged vertex is {drag['point_distance_m']} m from the point")
moved = drag["resolved_move_m"]
if not 0.005 <= -moved[2] <= 0.015:
    failures.append(f"the re-solved point moved {moved} m, asked 1 cm down")
if not (step["resolve"]["converged"] and step["resolve"]["certificate"] == "certified"):
    failures.append(f"re-solve: {step['resolve']}")
print(f"drag: vertex {drag['vertex']}, s = {s}, dg {dg:.4f}; predicted {predicted}, "
      f"re-solved {moved}")
# The two-parameter step: the normal equations of the least-squares fit.
two = steps[1]["drag"]
changes = [p["change"] for p in two["parameters"]]
rows, wanted = [], []
for d in two["drags"]:
    for c in range(3):
        rows.append([d["sensitivity_m_per_unit"][j][c] for j in range(len(changes))])
        wanted.append(d["by_m"][c])
fit = [dot(row, changes) - w for row, w in zip(rows, wanted)]
for j in range(len(changes)):
    column = [row[j] for row in rows]
    if not abs(dot(column, fit)) <= 1e-9 * math.sqrt(dot(column, column)) * 0.01:
        failures.append(f"parameter {j}: S^T (S dg - dd) = {dot(column, fit)}, not 0")
if not (changes[0] > 0 and changes[1] < 0):
    failures.append(f"front down and back up: changes {changes}")
if not steps[1]["resolve"]["certificate"] == "certified":
    failures.append(f"two drags: {steps[1]['resolve']}")
print(f"two drags: changes {changes}; moves {[d['resolved_move_m'] for d in two['drags']]}")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
