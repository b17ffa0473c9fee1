#!/usr/bin/env bash
# `sartor drape` end to end on a coarsely meshed garment (a case file of
# cases/garments): the outputs it writes and the physics of the result: the
# drape converged (dynamics and the settling static solve), sewn gradually
# (drape's default), the seams closed, no vertex deeper in the body than the
# contact offset, the body's reaction balancing the garment's weight, and the
# garment resting on the body rather than squeezing it (the normal forces sum
# to less than three times the weight: sewn at once, the T-shirt's seams
# dragged it into the shoulders, which then pressed on it with 3,000 N).
#
#   drape_garment.sh SARTOR PATTERN CASE OUT_DIR SEAMS
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: $0 SARTOR PATTERN CASE OUT_DIR SEAMS" >&2; exit 2; }
sartor=$1 pattern=$2 case=$3 dir=$4 seams=$5
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
"$sartor" drape "$pattern" -options_file_yaml "$case" --output "$dir"
for f in garment.obj seams.json drape_seams.json construct.json placement.svg body.obj final.obj \
         result.h5 result.xmf series.h5 series.xmf dynamics.csv summary.json \
         petsc_options.txt drape.png; do
  [ -s "$dir/$f" ] || { echo "drape_garment: $dir/$f missing" >&2; exit 1; }
done
"$python" - "$dir" "$seams" <<'PY'
import json, math, os, sys
d, seams = sys.argv[1], int(sys.argv[2])
s = json.load(open(os.path.join(d, "summary.json")))
drape = s["drape"]
assert s["converged"] and drape["converged"] and drape["equilibrium_checked"], s["dynamics"]["reason"]
assert s["dynamics"]["settle"]["converged"], s["dynamics"]["settle"]
assert s["seams"]["seams"] == seams, s["seams"]
assert s["seams"]["sewing_tension_N_per_m"] == 10 and s["seams"]["sewing_end_time_s"] == 1, s["seams"]
assert s["mesh"]["triangles"] < 1000, s["mesh"]  # the case file's coarse mesh
# Seam springs close to within the force over their stiffness: 0.1 mm here.
assert drape["largest_seam_gap_m"] < 5e-4, drape
# Penetration is measured from the offset surface: deeper than the offset
# means a vertex inside the body.
assert drape["max_penetration_m"] < drape["contact_offset_m"], drape
# Static equilibrium after the settle: the body carries the whole weight.
weight = math.hypot(*drape["weight_N"])
assert abs(weight - 9.80665 * 0.25 * drape["material_area_m2"]) < 1e-9 * weight, drape
# The settle stops once the residual's norm is below 1e-6 of the weight
# (drape's -snes_atol), so the net force may come out at that level or a few
# times it (the pants: 1.008e-6 on one machine): 1e-5 keeps a margin above
# the solver's tolerance, and a drape off equilibrium is far above it.
assert drape["relative_imbalance"] < 1e-5, drape
assert abs(drape["body_reaction_N"][2] - weight) < 1e-6 * weight, drape
body = s["contact"]["bodies"][0]
# It touches the body: by vertices, or by the samples of its edges (which
# may hold every vertex off the offset layer on convex parts).
assert body["contacting_vertices"] + body["contacting_edge_samples"] > 0, body
normal = math.hypot(*body["normal_force_N"])
assert normal < 3 * weight, f"the body presses on the garment with {normal} N (weight {weight} N)"
print("drape: %d triangles, gap %.2e m, penetration %.2e m, imbalance %.1e, normal force %.2f N "
      "for %.2f N, drape %.1f s"
      % (s["mesh"]["triangles"], drape["largest_seam_gap_m"], drape["max_penetration_m"],
         drape["relative_imbalance"], normal, weight, drape["timing_s"]["drape"]))
PY
