#!/usr/bin/env bash
# A creased sample (docs/pleats.md) constructed and draped coarsely by the
# static minimiser with cloth self-contact: the construction has the
# creases (and the pleat generator's stitches) asked for, the panels start
# pre-folded (each crease at its angle in garment.obj), the drape is
# certified with no vertex inside the body and the seams closed, and every
# crease stays folded on its side by at least MIN_DEG degrees
# (postproc/pleat_shape.py).
#
#   drape_pleats.sh SARTOR PATTERN CASE OUT_DIR POSTPROC_DIR CREASES STITCHES PLEATS MIN_DEG
set -euo pipefail
[ $# -eq 9 ] || {
  echo "usage: $0 SARTOR PATTERN CASE OUT_DIR POSTPROC_DIR CREASES STITCHES PLEATS MIN_DEG" >&2
  exit 2
}
sartor=$1 pattern=$2 case=$3 dir=$4 postproc=$5
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
"$sartor" drape "$pattern" -options_file_yaml "$case" --output "$dir" --no-plot
"$python" "$postproc/pleat_shape.py" "$dir" --json "$dir/pleats.json"
"$python" - "$dir" "$6" "$7" "$8" "$9" <<'PY'
import json, os, sys
d = sys.argv[1]
creases, stitches, pleats, min_deg = int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
c = json.load(open(os.path.join(d, "construct.json")))
s = json.load(open(os.path.join(d, "summary.json")))
p = json.load(open(os.path.join(d, "pleats.json")))
assert len(c["creases"]) == creases, c["creases"]
assert len(c["stitches"]) == stitches, c["stitches"]
assert p["pleats"] == pleats, p
for row in p["creases"]:
    # Pre-folded: each crease starts within 9 degrees of its rest angle (the
    # wrap onto the body bends a pleated panel only between its creases, and
    # turns a lapel's narrow region by 8 degrees).
    assert abs(row["start_deg"] - row["rest_deg"]) < 9.0, row
drape = s["drape"]
assert s["converged"] and drape["converged"], drape
assert drape["certificate"] == "certified", drape["certificate"]
assert drape["max_penetration_m"] < drape["contact_offset_m"], drape  # no vertex inside the body
assert drape["largest_seam_gap_m"] < 5e-4, drape
assert "self_contact" in s["contact"], s["contact"]  # the case's self-contact was on
for row in p["creases"]:
    assert row["final_deg"] * row["rest_deg"] > 0 and abs(row["final_deg"]) > min_deg, row
print("%s: %d triangles, drape %.1f s, penetration %.2e m, crease angles %s, pleats formed %d of %d"
      % (os.path.basename(d), s["mesh"]["triangles"], drape["timing_s"]["drape"],
         drape["max_penetration_m"], [round(r["final_deg"]) for r in p["creases"]],
         p["pleats_formed"], p["pleats"]))
PY
