#!/bin/bash
# Bodies with skeletons in garment construction: the mannequin sized to a
# measurement set, and the same body exported by `sartor body` as OBJ +
# skeleton and read back; TAGCON's torso cylinder follows the waist. Bodies
# without a skeleton are refused with a message naming the option. A drape
# on an exported OBJ body with its skeleton is certified, and so is its edit
# (the body's bone intervals in the push-out).
# Usage: body_skeleton_construct.sh SARTOR DATA_DIR PATTERN_DIR OUT
set -euo pipefail
sartor=$1 data=$2 patterns=$3 out=$4
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$sartor" body --measurements "$data/measurements_small.json" --pose elbow_l:30 --no-plot \
  --output "$out/body" > "$out/body.log"
grep -q "lacks" "$out/body.log" && fail "the small set is complete, yet defaults were reported"
for f in body.obj skeleton.json summary.json; do [[ -s $out/body/$f ]] || fail "no $f"; done

torso_top() { # construct.json -> the torso cylinder's top z
  /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); \
print([c['top'][2] for c in d['cylinders'] if c['cylinder']=='torso'][0])" "$1"
}
"$sartor" construct "$patterns/skirt.json" --body "mannequin measurements=$data/measurements_small.json" \
  --output "$out/sized" > /dev/null
"$sartor" construct "$patterns/skirt.json" \
  --body "mesh file=$out/body/body.obj skeleton=$out/body/skeleton.json" --output "$out/obj" > /dev/null
for run in sized obj; do
  top=$(torso_top "$out/$run/construct.json")
  # The small set's waistToFloor is 980 mm (the default's 1080).
  /usr/bin/python3 -c "import sys; sys.exit(abs($top - 0.98) > 0.002)" ||
    fail "$run: torso cylinder top at z = $top, expected the waist at 0.98"
done

if "$sartor" construct "$patterns/skirt.json" --body "mesh file=$out/body/body.obj" \
  --output "$out/bad" > "$out/bad.log" 2>&1; then fail "a mesh without skeleton was accepted"; fi
grep -q "option --body: mesh needs skeleton=" "$out/bad.log" || fail "message: $(cat "$out/bad.log")"
if "$sartor" drape "$patterns/skirt.json" --body "sphere radius=0.3" --output "$out/bad" \
  > "$out/bad.log" 2>&1; then fail "drape accepted a sphere"; fi
grep -q "the body must have a skeleton" "$out/bad.log" || fail "message: $(cat "$out/bad.log")"
# A drape on an OBJ body with a skeleton: the default mannequin exported and
# read back, the sample skirt at 8 cm with friction. Its distance is
# smoothed by default (0.1 mm; exact, edge contact samples settle on the
# polygonal body's creases and the minimiser stalls): certified, on the body.
"$sartor" body --no-plot --output "$out/default" > /dev/null
obj="mesh file=$out/default/body.obj skeleton=$out/default/skeleton.json"
"$sartor" drape "$patterns/skirt.json" --edge-length 0.08 -contact_stiffness_factor 10 \
  --body "$obj mu=0.3" --output "$out/drape_obj" --no-plot > "$out/drape_obj.log" 2>&1 ||
  fail "drape on the OBJ body: $(tail -n 2 "$out/drape_obj.log")"
/usr/bin/python3 - "$out/drape_obj/summary.json" <<'PY' || fail "drape on the OBJ body: see above"
import json, sys
s = json.load(open(sys.argv[1]))
body = s["contact"]["bodies"][0]["body"]
assert "distance smoothed over 0.0001 m" in body and "mu_s=0.3" in body, body
assert s["certificate"]["certified"], s["certificate"]["verdict"]
assert s["drape"]["outcome"]["end"] == "on_body", s["drape"]["outcome"]
print("skirt on the OBJ body: certified, %s" % body)
PY
# Its edit: the thesis' bone intervals index the body's triangles, and the
# start's vertices they place outside are not asked of the body.
"$sartor" edit "$out/drape_obj" "$patterns/../edit/skirt_hem.yaml" --no-plot --no-edit-outputs \
  --output "$out/edit_obj" > "$out/edit_obj.log" 2>&1 ||
  fail "edit on the OBJ body: $(tail -n 2 "$out/edit_obj.log")"
/usr/bin/python3 - "$out/edit_obj/summary.json" <<'PY' || fail "edit on the OBJ body: see above"
import json, sys
s = json.load(open(sys.argv[1]))
index = s["edit"]["bone_intervals"]
assert len(index) == 1 and index[0]["bones"] == 20 and index[0]["intervals_outside"] == 0, index
assert index[0]["triangles"] == 36364 and index[0]["intervals"] == 475, index
step = s["edit"]["steps"][0]
asked = step["start_pushed_out"]["body_queries"]
assert asked < s["mesh"]["vertices"] / 10, (asked, s["mesh"]["vertices"])
assert step["resolve"]["certified"], step["resolve"]
print("edit on the OBJ body: %d of %d vertices asked of the body, certified" % (asked, s["mesh"]["vertices"]))
PY
if "$sartor" drape "$patterns/skirt.json" --body "$obj smoothing=-1" --output "$out/bad" \
  > "$out/bad.log" 2>&1; then fail "smoothing=-1 was accepted"; fi
grep -q "smoothing must lie in \[0, 0.01\] m, got -1" "$out/bad.log" || fail "message: $(cat "$out/bad.log")"
echo "bodies with skeletons: OK"
