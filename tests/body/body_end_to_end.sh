#!/usr/bin/env bash
# `sartor body` end to end:
#
#   body_end_to_end.sh SARTOR DATA_DIR WORKDIR
#
# 1. The default mannequin: summary.json says closed 2-manifold, one piece of
#    genus 0, height 1.70-1.80 m, feet on z = 0, positive volume of a human
#    (0.04-0.10 m^3); skeleton.json has the documented format and bones; the
#    written body.obj reads back as a body (`sartor body --body body.obj`)
#    with the same triangle count and volume; body.png is made when
#    /usr/bin/python3 has matplotlib.
# 2. DATA_DIR/cube.obj (quads): 12 triangles, volume 1, area 6, height 1.
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR DATA_DIR WORKDIR" >&2; exit 2; }
sartor=$1 data=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"

plot=--no-plot
if "$python" -c "import numpy, matplotlib" 2>/dev/null; then plot=; fi
"$sartor" body $plot --output "$work/mannequin"
"$sartor" body --body "$work/mannequin/body.obj" --no-plot --output "$work/reread"
"$sartor" body --body "$data/cube.obj" --no-plot --output "$work/cube"

"$python" - "$work" "$plot" <<'PY'
import json, os, sys
work, plot = sys.argv[1], sys.argv[2]
failures = []
def check(condition, message):
    if not condition:
        failures.append(message)
summary = json.load(open(f"{work}/mannequin/summary.json"))["body"]
check(summary["kind"] == "mannequin", f"kind {summary['kind']}")
check(summary["closed"] and summary["manifold"] and summary["outward_oriented"], "not a closed body")
check(summary["components"] == 1 and summary["genus"] == 0,
      f"components {summary['components']}, genus {summary['genus']}")
check(1.70 <= summary["height_m"] <= 1.80, f"height {summary['height_m']}")
check(abs(summary["bounding_box_m"]["lower"][2]) < 1e-9, "feet not on z = 0")
check(0.04 < summary["volume_m3"] < 0.10, f"volume {summary['volume_m3']}")
check(10000 <= summary["triangles"] <= 40000, f"triangles {summary['triangles']}")
skeleton = json.load(open(f"{work}/mannequin/skeleton.json"))
check(skeleton["format"] == "sartor-skeleton" and skeleton["version"] == 1, "skeleton format")
names = [bone["name"] for bone in skeleton["bones"]]
for required in ["pelvis", "torso", "neck", "head", "upper_arm_l", "upper_arm_r", "forearm_l",
                 "forearm_r", "thigh_l", "thigh_r", "shin_l", "shin_r"]:
    check(required in names, f"skeleton lacks {required}")
for bone in skeleton["bones"]:
    check(bone["parent"] is None or bone["parent"] in names[:names.index(bone["name"])],
          f"{bone['name']}: parent {bone['parent']} is not listed before it")
    check(len(bone["start"]) == 3 and len(bone["end"]) == 3, f"{bone['name']}: joints")
    check(bone["start_radius"] > 0 and bone["end_radius"] > 0, f"{bone['name']}: radii")
reread = json.load(open(f"{work}/reread/summary.json"))["body"]
check(reread["triangles"] == summary["triangles"], "body.obj reads back with another size")
check(abs(reread["volume_m3"] - summary["volume_m3"]) < 1e-12, "body.obj volume changed")
check(not os.path.exists(f"{work}/reread/skeleton.json"), "a file body got a skeleton")
cube = json.load(open(f"{work}/cube/summary.json"))["body"]
check(cube["triangles"] == 12 and abs(cube["volume_m3"] - 1) < 1e-12
      and abs(cube["area_m2"] - 6) < 1e-12 and cube["height_m"] == 1, f"cube {cube}")
if not plot:
    check(os.path.getsize(f"{work}/mannequin/body.png") > 10000, "body.png missing or empty")
if failures:
    sys.exit("body_end_to_end: FAILED\n  " + "\n  ".join(failures))
print("body_end_to_end: mannequin, its OBJ round trip and the cube are as expected")
PY
