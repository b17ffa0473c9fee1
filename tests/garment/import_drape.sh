#!/usr/bin/env bash
# From a FreeSewing-style SVG to a drape (docs/patterns.md): `sartor import`
# with the tag file, then `sartor drape` with a user seams file that
# re-declares the centre back seam. Checks that the darts are sewn leg to
# leg (4 dart seams, no dart leg unseamed), the user's seam replaced
# TAGCON's of the same lines, the drape converged and ended on the body
# (drape.outcome), and the echoed options keep the user's seams file.
# With TWISTED_SEAMS (a seams file sewing the centre back the wrong way
# round, waist to hem) the skirt slides down the body: drape must report
# that (closing line, summary.json, exit status 1), not "converged".
#
#   import_drape.sh SARTOR CASES_IMPORT CASE OUT_DIR [TWISTED_SEAMS]
set -euo pipefail
[ $# -eq 4 ] || [ $# -eq 5 ] ||
  { echo "usage: $0 SARTOR CASES_IMPORT CASE OUT_DIR [TWISTED_SEAMS]" >&2; exit 2; }
sartor=$1 cases=$2 case=$3 dir=$4 twisted=${5:-}
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
mkdir -p "$dir"
"$sartor" import "$cases/pencil_skirt.svg" --tags "$cases/pencil_skirt_tags.json" \
  --output "$dir/pencil_skirt.json" | tee "$dir/import.log"
grep -q "wrote $dir/pencil_skirt.json: 3 panels in 2 packs, valid" "$dir/import.log"
if [ -n "$twisted" ]; then
  status=0
  # In dynamics it slides (the static minimiser stops with the seams open).
  "$sartor" drape "$dir/pencil_skirt.json" -options_file_yaml "$case" --seams-file "$twisted" \
    --analysis dynamic --output "$dir/twisted" --no-plot > "$dir/twisted.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] || { echo "drape exited with $status, expected 1" >&2; exit 1; }
  grep -q "garment slid down 0\.[1-9][0-9]* m)" "$dir/twisted.log"
  grep -q "error: the drape did not drape the garment: it ended slid down" "$dir/twisted.log"
  "$python" - "$dir/twisted" <<'PY'
import json, os, sys
drape = json.load(open(os.path.join(sys.argv[1], "summary.json")))["drape"]
assert not drape["converged"] and drape["outcome"]["end"] == "slid_down", drape["outcome"]
assert drape["outcome"]["centroid_drop_m"] > drape["outcome"]["drop_tolerance_m"], drape
print("twisted centre back: slid down %.3f m" % drape["outcome"]["centroid_drop_m"])
PY
  exit 0
fi
"$sartor" drape "$dir/pencil_skirt.json" -options_file_yaml "$case" \
  --seams-file "$cases/pencil_skirt_seams.json" --output "$dir/drape" --no-plot | tee "$dir/drape.log"
tail -n 1 "$dir/drape.log" | grep -qE "\((static minimiser|dynamics), converged\)"
grep -q -- "-seams_file $cases/pencil_skirt_seams.json" "$dir/drape/petsc_options.txt"
"$python" - "$dir/drape" <<'PY'
import json, os, sys
d = sys.argv[1]
c = json.load(open(os.path.join(d, "construct.json")))
kinds = [s["kind"] for s in c["seams"]]
assert kinds.count("dart") == 4, kinds
user = [s for s in c["seams"] if s["kind"] == "user"]
assert len(user) == 1 and {user[0]["line_a"], user[0]["line_b"]} == {"back_8", "back_2_8"}, user
assert kinds.count("intra_pack") == 0, kinds  # TAGCON's centre back seam was replaced
dart_legs = {s[k] for s in c["seams"] if s["kind"] == "dart" for k in ("line_a", "line_b")}
unseamed = {l["id"] for l in c["lines"] if "unseamed" in l}
assert not dart_legs & unseamed, dart_legs & unseamed
s = json.load(open(os.path.join(d, "summary.json")))
drape = s["drape"]
assert drape["converged"] and drape["outcome"]["end"] == "on_body", drape["outcome"]
assert abs(drape["outcome"]["centroid_drop_m"]) < drape["outcome"]["drop_tolerance_m"], drape
print("pencil skirt: %d triangles, centroid drop %.3f m, lowest point %.3f m, gap %.1e m"
      % (s["mesh"]["triangles"], drape["outcome"]["centroid_drop_m"],
         drape["outcome"]["lowest_point_m"], drape["largest_seam_gap_m"]))
PY
