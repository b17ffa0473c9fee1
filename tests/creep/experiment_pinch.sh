#!/usr/bin/env bash
# The pinch-and-release test (thesis Fig. 5.8, cases/creep/pinch.yaml) on the
# case's 16 x 16 mesh, the pinch let go after 1 s and after 1 h of holding:
# both runs converge and reach their end time, and 60 s after the release the
# 1 h variant keeps more deformation: a residual sag at least 1.5 times and a
# mean non-elastic strain at least 3 times the 1 s variant's.
#   experiment_pinch.sh SARTOR CASE.yaml POSTPROC.py WORKDIR
set -euo pipefail
sartor=$1 case=$2 postproc=$3 work=$4
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$case" --output "$work/held_1s" > "$work/held_1s.log"
"$sartor" run "$case" --pin-release 1:3600.5 --time-end 3660.5 --output-interval 300 \
  --output "$work/held_1h" > "$work/held_1h.log"
"$python" "$postproc" pinch "$work/held_1s" "$work/held_1h" --labels "1 s,1 h" --json "$work/pinch.json"
"$python" - "$work/pinch.json" "$work" "$(dirname "$0")" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[3])
from experiment_checks import unfinished
short, long = json.load(open(sys.argv[1]))["runs"]
failures = unfinished((short, long), "held ")
for key, factor in (("residual_sag_m", 1.5), ("residual_nonelastic_strain", 3.0)):
    if not short[key] > 0.0:
        failures.append(f"held 1 s: no {key} ({short[key]})")
    if not long[key] > factor * short[key]:
        failures.append(f"{key}: held 1 h {long[key]:.4g} is not {factor} x held 1 s {short[key]:.4g}")
# Let go: the pinch hangs below the sheet's plane instead of sitting at its place.
for run in ("held_1s", "held_1h"):
    z = [float(l.split()[3]) for l in open(f"{sys.argv[2]}/{run}/final.obj") if l.startswith("v ")]
    if not min(z) < -1e-3:
        failures.append(f"{run}: the released pinch does not hang (lowest z {min(z):.3g} m)")
if failures:
    sys.exit("\n".join(failures))
PY
