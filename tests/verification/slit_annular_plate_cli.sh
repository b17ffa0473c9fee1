#!/usr/bin/env bash
# cases/fe/slit_annular_plate.yaml from the command line, once refined (1,056
# triangles, about 15 s): the boxes pin the clamp sector (both of its radial
# grid lines) and load the other edge of the slit only, the whole 3.2 N
# reaches the pins, and the lift of the outer corner B is within 5 % of Sze,
# Liu & Lo's 17.528 m (measured -2.1 %). Bad annulus arguments are refused.
#   slit_annular_plate_cli.sh SARTOR CASE.yaml WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASE.yaml WORKDIR" >&2; exit 2; }
sartor=$1 case=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$sartor" run "$case" --mesh-refine 1 --no-plot --output "$work/run" > "$work/run.log"
python3 - "$work/run/summary.json" << 'PY' || fail "summary: see above"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["converged"], "not converged"
# 9 vertices across the radii on each of the clamp's 3 radial grid lines.
assert s["mesh"]["pinned_vertices"] == 27, s["mesh"]
reaction = s["pin_reaction_N"]
assert abs(reaction[2] + 3.2) < 1e-3 and abs(reaction[0]) < 1e-3, reaction
lift = s["probe"]["displacement_m"][2] + s["probe"]["initial_position_m"][2]
assert abs(lift / 17.528 - 1) < 0.05, lift
print("W_B = %.4f m (%+.2f %% against Sze et al.)" % (lift, 100 * (lift / 17.528 - 1)))
PY

if "$sartor" run "$case" --mesh-inner-radius 12 --output "$work/bad" > "$work/bad.log" 2>&1; then
  fail "inner radius above the outer one accepted"
fi
grep -q "annulus: outer_radius must be a finite number above inner_radius" "$work/bad.log" ||
  fail "bad.log: $(cat "$work/bad.log")"
echo "ok"
