#!/usr/bin/env bash
# The pinch-and-release test (thesis Fig. 5.8, cases/creep/pinch.yaml) on the
# case's 16 x 16 mesh, the pinch released after 1 s and after 1 h of holding:
# both runs converge and reach their end time, and 60 s after the release the
# 1 h variant keeps more deformation: a residual sag at least 1.5 times and a
# mean non-elastic strain at least 3 times the 1 s variant's.
#   experiment_pinch.sh SARTOR CASE.yaml POSTPROC.py WORKDIR
set -euo pipefail
sartor=$1 case=$2 postproc=$3 work=$4
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "skip: $python lacks h5py/numpy"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$case" --output "$work/held_1s" > "$work/held_1s.log"
"$sartor" run "$case" --pin-motion "0:0,0,0; 0.5:0,0,0.04; 3600.5:0,0,0.04; 3601:0,0,0" \
  --time-end 3661 --output-interval 300 --output "$work/held_1h" > "$work/held_1h.log"
"$python" "$postproc" pinch "$work/held_1s" "$work/held_1h" --labels "1 s,1 h" --json "$work/pinch.json"
"$python" - "$work/pinch.json" <<'PY'
import json, sys
short, long = json.load(open(sys.argv[1]))["runs"]
failures = [f"held {r['label']}: converged {r['converged']}, completed {r['completed']}"
            for r in (short, long) if not (r["converged"] and r["completed"])]
for key, factor in (("residual_sag_m", 1.5), ("residual_nonelastic_strain", 3.0)):
    if not short[key] > 0.0:
        failures.append(f"held 1 s: no {key} ({short[key]})")
    if not long[key] > factor * short[key]:
        failures.append(f"{key}: held 1 h {long[key]:.4g} is not {factor} x held 1 s {short[key]:.4g}")
if failures:
    sys.exit("\n".join(failures))
PY
