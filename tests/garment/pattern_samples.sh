#!/usr/bin/env bash
# `sartor pattern` on the sample patterns: the files it writes, the SVG
# well-formed (xmllint where installed), the meshes' quality and areas, and
# lines.json consistent with the OBJ files.
#
#   pattern_samples.sh SARTOR SAMPLES_DIR OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR SAMPLES_DIR OUT_DIR" >&2; exit 2; }
sartor=$1 samples=$2 out=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }

"$sartor" pattern --help | grep -q "lines.json" \
  || { echo "pattern_samples: --help does not describe the output" >&2; exit 1; }

for name in skirt tshirt; do
  dir="$out/$name"
  rm -rf "$dir"
  "$sartor" pattern "$samples/$name.json" --output "$dir" --edge-length 0.03 --min-angle 28
  if command -v xmllint > /dev/null; then
    xmllint --noout "$dir/pattern.svg"
  fi
  "$python" - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]
summary = json.load(open(os.path.join(d, "summary.json")))
lines = json.load(open(os.path.join(d, "lines.json")))["lines"]
failures = []
def obj_counts(path):
    v = f = 0
    for row in open(path):
        v += row.startswith("v ")
        f += row.startswith("f ")
    return v, f
total_v = 0
for panel in summary["panels"]:
    v, f = obj_counts(os.path.join(d, panel["obj"]))
    total_v += v
    if (v, f) != (panel["vertices"], panel["triangles"]):
        failures.append(f"{panel['id']}: OBJ has {v} v, {f} f; summary says "
                        f"{panel['vertices']}, {panel['triangles']}")
    if panel["min_angle_regular_deg"] < 28 - 1e-9:
        failures.append(f"{panel['id']}: min angle {panel['min_angle_regular_deg']} < 28")
    if abs(panel["mesh_area_m2"] - panel["boundary_polygon_area_m2"]) > 1e-12:
        failures.append(f"{panel['id']}: mesh area {panel['mesh_area_m2']} is not the boundary's")
    if abs(panel["mesh_area_m2"] - panel["outline_area_m2"]) > 1e-3 * panel["outline_area_m2"]:
        failures.append(f"{panel['id']}: mesh area {panel['mesh_area_m2']}, outline "
                        f"{panel['outline_area_m2']}")
v, f = obj_counts(os.path.join(d, "pattern.obj"))
if v != total_v or f != summary["triangles"]:
    failures.append(f"pattern.obj has {v} v, {f} f")
for line in lines:
    if line["kind"] == "outline" and len(line["vertices"]) != line["pieces"] + 1:
        failures.append(f"line {line['id']}: {len(line['vertices'])} vertices, {line['pieces']} pieces")
    if len(line["pattern_vertices"]) != len(line["vertices"]):
        failures.append(f"line {line['id']}: pattern_vertices differ in length")
if failures:
    sys.exit("pattern_samples: FAILED\n  " + "\n  ".join(failures))
print(f"pattern_samples: {d}: {len(summary['panels'])} panels, {summary['triangles']} triangles, "
      f"min angle {summary['min_angle_deg']:.2f}")
PY
done
