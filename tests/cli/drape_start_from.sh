#!/bin/bash
# sartor drape --start-from (docs/drape.md#starting-from-another-drape): the
# coarse skirt with darts is draped, then
#  1. draped again starting from its own drape (one sewing stage): every
#     vertex starts where it was, so the drape is certified and ends within
#     1 mm of the first (fresh friction anchors may let it settle a little);
#  2. a version of the pattern with the hem 3 cm lower starts from the
#     first drape: the vertices beyond the old panels are exactly those of
#     the new mesh below the old hem (counted here from the new garment's
#     material coordinates, u < 0), at most 3 cm beyond, and the drape is
#     certified;
#  3. a pattern with a panel the old drape lacks, --levels 2, and a folder
#     without a drape are refused.
# Usage: drape_start_from.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
pattern="$root/cases/patterns/skirt_darts.json"
options=(-options_file_yaml "$root/cases/garments/skirt_coarse.yaml" --no-plot)
"$sartor" drape "$pattern" "${options[@]}" --output "$out/first" > "$out/first.log" 2>&1 ||
  { cat "$out/first.log"; exit 1; }
"$sartor" drape "$pattern" "${options[@]}" --start-from "$out/first" --sewing-stages 1 \
  --output "$out/again" > "$out/again.log" 2>&1 || { cat "$out/again.log"; exit 1; }
/usr/bin/python3 - "$pattern" "$out" <<'PY'
import json, sys
pattern, out = sys.argv[1], sys.argv[2]
document = json.load(open(pattern))
for panel in document["panels"]:
    for line in panel["outline"]:
        line["points"] = [[x, y - 0.03 if y == 0 else y] for x, y in line["points"]]
json.dump(document, open(f"{out}/longer.json", "w"))
PY
"$sartor" drape "$out/longer.json" "${options[@]}" --start-from "$out/first" \
  --output "$out/longer" > "$out/longer.log" 2>&1 || { cat "$out/longer.log"; exit 1; }
/usr/bin/python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
failures = []
def vertices(path):
    return [list(map(float, line.split()[1:4])) for line in open(path) if line.startswith("v ")]
first, again = vertices(f"{out}/first/final.obj"), vertices(f"{out}/again/final.obj")
moved = max(math.dist(a, b) for a, b in zip(first, again))
summary = json.load(open(f"{out}/again/summary.json"))
if not (summary["drape"]["certificate"] == "certified" and moved <= 1e-3):
    failures.append(f"from its own drape: {summary['drape']['certificate']}, moved {moved} m")
start = summary["drape"]["start_from"]
if start["extrapolated_vertices"] != 0 or start["vertices"] != len(first):
    failures.append(f"from its own drape: {start}")
print(f"from its own drape: {summary['solver']['newton_iterations']} Newton iterations, "
      f"{moved:.2e} m from it")
# The new mesh's vertices below the old hem: u = y < 0 (the grain is vertical).
below = set()
faces = []
for line in open(f"{out}/longer/garment.obj"):
    if line.startswith("f "):
        for corner in line.split()[1:]:
            v, t = (int(i) - 1 for i in corner.split("/")[:2])
            faces.append((v, t))
uv = [list(map(float, line.split()[1:3])) for line in open(f"{out}/longer/garment.obj")
      if line.startswith("vt ")]
below = {v for v, t in faces if uv[t][0] < -1e-9}
summary = json.load(open(f"{out}/longer/summary.json"))
start = summary["drape"]["start_from"]
if start["extrapolated_vertices"] != len(below):
    failures.append(f"hem 3 cm lower: {start['extrapolated_vertices']} vertices extended, "
                    f"{len(below)} lie below the old hem")
if not 0.03 - 1e-9 <= start["farthest_beyond_old_panel_m"] <= 0.03 + 1e-9:
    failures.append(f"hem 3 cm lower: farthest {start['farthest_beyond_old_panel_m']} m beyond")
if summary["drape"]["certificate"] != "certified":
    failures.append(f"hem 3 cm lower: {summary['drape']['certificate']}")
print(f"hem 3 cm lower: {len(below)} vertices below the old hem, "
      f"{summary['solver']['newton_iterations']} Newton iterations")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
# Refusals: a panel the old drape lacks, more than one level, no drape.
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
document = json.load(open(f"{out}/longer.json"))
document["panels"][1]["id"] = "skirt_lining"
json.dump(document, open(f"{out}/renamed.json", "w"))
PY
expect_refusal() {
  local message=$1
  shift
  local status=0
  "$sartor" drape "$@" --no-plot --output "$out/bad" > "$out/bad.log" 2>&1 || status=$?
  if [ "$status" != 2 ] || ! grep -q "$message" "$out/bad.log"; then
    echo "expected exit 2 and '$message', got $status:" >&2
    cat "$out/bad.log" >&2
    exit 1
  fi
}
expect_refusal "option --start-from: $out/first has no panel 'skirt_lining'" \
  "$out/renamed.json" "${options[@]}" --start-from "$out/first"
expect_refusal "option --start-from: the drape starts on the finest mesh; give --levels 1" \
  "$pattern" --levels 2 --start-from "$out/first"
expect_refusal "option --start-from: $out: no final.obj" "$pattern" "${options[@]}" \
  --start-from "$out"
echo "refusals: a panel not draped, --levels 2, no drape"
