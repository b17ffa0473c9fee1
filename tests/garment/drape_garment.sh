#!/usr/bin/env bash
# `sartor drape` end to end on the skirt, coarsely meshed
# (cases/garments/skirt_coarse.yaml): the outputs it
# writes and the physics of the result: the drape converged (dynamics and the
# settling static solve), the seams closed, no vertex deeper in the body than
# the contact offset, the body's reaction balancing the garment's weight.
#
#   drape_skirt.sh SARTOR SAMPLES_DIR OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR SAMPLES_DIR OUT_DIR" >&2; exit 2; }
sartor=$1 samples=$2 out=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "skip: $python not found"; exit 77; }
dir="$out/drape_skirt"
rm -rf "$dir"
"$sartor" drape "$samples/skirt.json" -options_file_yaml "$samples/../garments/skirt_coarse.yaml" \
  --output "$dir"
for f in garment.obj seams.json drape_seams.json construct.json placement.svg body.obj final.obj \
         result.h5 result.xmf series.h5 series.xmf dynamics.csv summary.json \
         petsc_options.txt drape.png; do
  [ -s "$dir/$f" ] || { echo "drape_skirt: $dir/$f missing" >&2; exit 1; }
done
"$python" - "$dir" <<'PY'
import json, math, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, "summary.json")))
drape = s["drape"]
assert s["converged"] and drape["converged"], s["dynamics"]["reason"]
assert s["dynamics"]["settle"]["converged"], s["dynamics"]["settle"]
assert s["seams"]["seams"] == 2, s["seams"]
assert s["mesh"]["triangles"] < 600, s["mesh"]  # the case file's coarse mesh
# Seam springs close to within the force over their stiffness: microns here.
assert drape["largest_seam_gap_m"] < 1e-4, drape
# Penetration is measured from the offset surface: deeper than the offset
# means a vertex inside the body.
assert drape["max_penetration_m"] < drape["contact_offset_m"], drape
# Static equilibrium after the settle: the body carries the whole weight.
weight = math.hypot(*drape["weight_N"])
assert abs(weight - 9.80665 * 0.25 * drape["material_area_m2"]) < 1e-9 * weight, drape
assert drape["relative_imbalance"] < 1e-6, drape
assert abs(drape["body_reaction_N"][2] - weight) < 1e-6 * weight, drape
assert s["contact"]["bodies"][0]["contacting_vertices"] > 0
print("drape_skirt: %d triangles, gap %.2e m, penetration %.2e m, imbalance %.1e, drape %.1f s"
      % (s["mesh"]["triangles"], drape["largest_seam_gap_m"], drape["max_penetration_m"],
         drape["relative_imbalance"], drape["timing_s"]["drape"]))
PY
