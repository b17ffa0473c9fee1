#!/usr/bin/env bash
# `sartor drape` on two static levels (docs/drape.md, "Levels"): the skirt at
# 8 cm, then at 4 cm from its drape prolonged, once with each
# --level-sewing. The coarse level is sewn in all eight stages; the finer one
# starts sewn and loaded, and is sewn again in all eight (all: its first
# stage unloaded) or only the last two (last-two: its first stage at the
# stage before the last's share of the load, 6/7, without friction). Every
# run must end certified as the single-level drape does: the body's
# reaction balancing the weight, the seams closed, no vertex inside the body.
# Then the skirt from 12 to 8 cm with the default (last-two): from that
# coarser start the frictionless stage's step bound stalled, and the finer
# level spent 1,225 Newton iterations (the stage its whole -snes_max_it);
# with the stalled stage solved again on stiffer contact, about 200.
#
#   drape_static_levels.sh SARTOR PATTERN OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR PATTERN OUT_DIR" >&2; exit 2; }
sartor=$1 pattern=$2 dir=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
for sewing in all last-two; do
  "$sartor" drape "$pattern" --edge-length 0.04 --coarsest-edge 0.08 --level-sewing "$sewing" \
    --no-plot --output "$dir/$sewing"
  "$python" - "$dir/$sewing" "$sewing" <<'PY'
import json, math, os, sys
s = json.load(open(os.path.join(sys.argv[1], "summary.json")))
sewing = sys.argv[2]
drape = s["drape"]
levels = drape["levels"]
assert [round(l["edge_length_m"], 12) for l in levels] == [0.08, 0.04], levels
coarse, fine = levels
assert coarse["analysis"] == "static" and coarse["converged"], coarse
assert fine["analysis"] == "static" and fine["converged"], fine
assert s["solver"]["minimiser"]["sewing_stages"] == 8, s["solver"]["minimiser"]
assert s["solver"]["minimiser"]["unconverged_stages"] == [], s["solver"]["minimiser"]
# The finer level's steps (those reported): its first stage's load factor.
first = s["load_steps"][0]["load_factor"]
expected = 6.0 / 7.0 if sewing == "last-two" else 0.0
assert abs(first - expected) < 1e-12, (sewing, s["load_steps"])
assert s["converged"] and drape["certificate"] == "certified", drape["certificate"]
weight = math.hypot(*drape["weight_N"])
assert abs(drape["body_reaction_N"][2] - weight) < 1e-6 * weight, drape
assert drape["largest_seam_gap_m"] < 5e-4, drape
assert drape["max_penetration_m"] < drape["contact_offset_m"], drape
print("drape_static_levels, %s: %d -> %d triangles, Newton %d + %d, gap %.1e m, "
      "penetration %.2e m" % (sewing, coarse["triangles"], fine["triangles"],
                               coarse["newton_iterations"], fine["newton_iterations"],
                               drape["largest_seam_gap_m"], drape["max_penetration_m"]))
PY
done
"$sartor" drape "$pattern" --edge-length 0.08 --coarsest-edge 0.12 --no-plot --output "$dir/from12"
"$python" - "$dir/from12" <<'PY'
import json, os, sys
s = json.load(open(os.path.join(sys.argv[1], "summary.json")))
fine = s["drape"]["levels"][1]
assert s["converged"] and s["drape"]["certificate"] == "certified", s["drape"]["certificate"]
assert fine["newton_iterations"] < 600, fine
print("drape_static_levels, from 12 cm: finer level %d Newton iterations, %d stalled stage(s) "
      "solved again" % (fine["newton_iterations"],
                        s["solver"]["minimiser"]["stalled_stage_resolves"]))
PY
