#!/usr/bin/env bash
# The push test (thesis Fig. 5.6, cases/creep/push.yaml) on an 8 x 8 mesh with
# E = 3000, 300, 30 N/m: every run converges and reaches its end time, and the
# residual bulge after withdrawal grows as E falls (each at least 20 % more
# than the last).
#   experiment_push.sh SARTOR CASE.yaml POSTPROC.py WORKDIR
set -euo pipefail
sartor=$1 case=$2 postproc=$3 work=$4
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
coarse=(--mesh-nx 8 --mesh-ny 8 --time-end 6 --output-interval 1)
runs=()
for modulus in 3000 300 30; do
  "$sartor" run "$case" "${coarse[@]}" --creep-parameters "$modulus,0.8,0.05,0.05" \
    --output "$work/E$modulus" > "$work/E$modulus.log"
  runs+=("$work/E$modulus")
done
"$python" "$postproc" push "${runs[@]}" --labels "E=3000,E=300,E=30" --json "$work/push.json"
# The picture of the three shapes (postproc/plot_shapes.py, beside the script).
"$python" "$(dirname "$postproc")/plot_shapes.py" "$work/E3000" "$work/E300" "$work/E30" \
  --labels "E = 3000,E = 300,E = 30" --output "$work/shapes.png"
[ -s "$work/shapes.png" ] || { echo "no picture of the shapes" >&2; exit 1; }
"$python" - "$work/push.json" "$(dirname "$0")" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2])
from experiment_checks import rising, unfinished
runs = json.load(open(sys.argv[1]))["runs"]
failures = unfinished(runs) + rising(runs, "residual_bulge_m", " m")
if failures:
    sys.exit("\n".join(failures))
PY
