#!/bin/bash
# sartor edit on the coarse sample skirt (cases/edit/skirt_hem.yaml): the hem
# lengthened by 2 cm in the pattern must lower the draped garment's lowest
# point by about 2 cm (the skirt hangs nearly straight below the hips: the
# edit's own size is the reference), the linear prediction must get that
# drop to within 30 % of it, the thesis' geometric route (the drape carried
# barycentrically onto the edited pattern) must lower it by about the edit's
# length too, the re-solve's certificate is reported, not assumed, and
# postproc/plot_edit.py draws the edit.
# Usage: edit_skirt_hem.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out"
"$sartor" edit "$root/cases/patterns/skirt.json" "$root/cases/edit/skirt_hem.yaml" \
  -options_file_yaml "$root/cases/garments/skirt_coarse.yaml" --output "$out" --no-plot \
  > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
grep -q "sartor edit: edit_01 ('hem 2 cm longer')" "$out.log"
for f in edit_01/pattern.svg edit_01/outlines.json edit_01/linear/final.obj edit_01/gmls/result.h5 \
         edit_01/geometric/final.obj \
         edit_01/resolved/final.obj final.obj; do
  test -s "$out/$f" || { echo "missing $f"; exit 1; }
done
/usr/bin/python3 - "$out/summary.json" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))
assert summary["command"] == "edit", summary["command"]
step = summary["edit"]["steps"][0]
low = step["lowest_point_z_m"]
drop = low["resolved"] - low["before"]
predicted = low["linear"] - low["before"]
print(f"lowest point: re-solved {drop:+.4f} m, linear prediction {predicted:+.4f} m")
assert -0.026 < drop < -0.012, f"the hem dropped {drop} m for a 2 cm edit"
assert abs(predicted - drop) < 0.3 * abs(drop), f"prediction {predicted} against {drop}"
geometric = low["geometric"] - low["before"]
print(f"geometric route: {geometric:+.4f} m")
assert -0.026 < geometric < -0.012, f"the geometric route dropped the hem {geometric} m"
assert set(step["error_against_resolved"]) == {"unchanged", "linear", "gmls", "geometric"}
resolve = step["resolve"]
assert resolve["converged"], resolve
# The verdict is the certificate's own: "certified" only when it says so.
assert (resolve["certificate"] == "certified") == resolve["certified"], resolve
cpu = step["cpu_s"]
assert cpu["resolve"] > 0 and cpu["drape_from_scratch"] > 0, cpu
assert step["gmls"]["designs"] == 1 and step["gmls"]["degree"] == 1, step["gmls"]
PY
# The picture of the edit: the pattern beside the re-solved drape.
/usr/bin/python3 "$root/postproc/plot_edit.py" "$out"
test -s "$out/edit_01/edit.png" || { echo "plot_edit.py wrote no edit_01/edit.png"; exit 1; }
