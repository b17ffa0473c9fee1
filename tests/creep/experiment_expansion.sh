#!/usr/bin/env bash
# The cylinder expansion test (thesis Fig. 5.7, cases/creep/expansion.yaml) on
# a 16 x 2 tube with lambda_load = 0.005, 0.025, 0.05 1/s: every run
# converges and reaches its end time; the excess circumference (mean warp
# eps_v + eps_p) and the slack tube's sag below the drum both grow with
# lambda_load (each at least 20 % more than the last).
#   experiment_expansion.sh SARTOR CASE.yaml POSTPROC.py WORKDIR
set -euo pipefail
sartor=$1 case=$2 postproc=$3 work=$4
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
coarse=(--mesh-segments 16 --mesh-rows 2 --output-interval 1)
runs=()
for rate in 0.005 0.025 0.05; do
  "$sartor" run "$case" "${coarse[@]}" --creep-parameters "300,0.8,$rate,0.05" \
    --output "$work/l$rate" > "$work/l$rate.log"
  runs+=("$work/l$rate")
done
"$python" "$postproc" expansion "${runs[@]}" --labels "ll=0.005,ll=0.025,ll=0.05" \
  --json "$work/expansion.json"
"$python" - "$work/expansion.json" "$(dirname "$0")" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2])
from experiment_checks import rising, unfinished
runs = json.load(open(sys.argv[1]))["runs"]
failures = unfinished(runs)
for key in ("excess_circumference", "sag_gap_m"):
    failures += rising(runs, key)
if failures:
    sys.exit("\n".join(failures))
PY
