#!/usr/bin/env bash
# The pleated skirt sample (docs/pleats.md) constructed and draped coarsely:
# the pleat generator's creases and stitches are in the construction, the
# panels start pre-folded (each crease at its angle in garment.obj), the
# drape converges with no vertex inside the body, the stitches closed, and
# the pleats stay folded (postproc/pleat_shape.py: every crease on the side
# of its rest angle and at least half of it).
#
#   drape_pleats.sh SARTOR PATTERN CASE OUT_DIR POSTPROC_DIR
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: $0 SARTOR PATTERN CASE OUT_DIR POSTPROC_DIR" >&2; exit 2; }
sartor=$1 pattern=$2 case=$3 dir=$4 postproc=$5
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
"$sartor" drape "$pattern" -options_file_yaml "$case" --output "$dir" --no-plot
"$python" "$postproc/pleat_shape.py" "$dir" --json "$dir/pleats.json"
"$python" - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]
c = json.load(open(os.path.join(d, "construct.json")))
s = json.load(open(os.path.join(d, "summary.json")))
p = json.load(open(os.path.join(d, "pleats.json")))
# Two panels with two knife pleats each: two creases and one waist stitch per pleat.
assert len(c["creases"]) == 8, c["creases"]
assert len(c["stitches"]) == 4, c["stitches"]
assert p["pleats"] == 4, p
for row in p["creases"]:
    # Pre-folded: each crease starts within 3 degrees of its rest angle
    # (the wrap onto the cylinder bends the panel only between creases).
    assert abs(row["start_deg"] - row["rest_deg"]) < 3.0, row
drape = s["drape"]
assert s["converged"] and drape["converged"] and drape["equilibrium_checked"], s["dynamics"]["reason"]
assert drape["max_penetration_m"] < drape["contact_offset_m"], drape  # no vertex inside the body
assert drape["largest_seam_gap_m"] < 5e-4, drape
for row in p["creases"]:
    assert row["final_deg"] * row["rest_deg"] > 0 and abs(row["final_deg"]) > 20, row
print("pleated skirt: %d triangles, drape %.1f s, penetration %.2e m, pleats formed %d of %d"
      % (s["mesh"]["triangles"], drape["timing_s"]["drape"], drape["max_penetration_m"],
         p["pleats_formed"], p["pleats"]))
PY
