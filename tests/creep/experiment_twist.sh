#!/usr/bin/env bash
# The twist test (thesis Fig. 5.10, cases/creep/twist.yaml) on a 16 x 4 tube
# with the five fabrics of Table 5.1 at ten times their lambdas: every run
# converges and reaches its end time, every fabric keeps some non-elastic
# strain, and cotton twill keeps more than nylon (at least 1.5 times).
#   experiment_twist.sh SARTOR CASE.yaml FABRIC_DIR POSTPROC.py WORKDIR
set -euo pipefail
sartor=$1 case=$2 fabrics=$3 postproc=$4 work=$5
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
coarse=(--mesh-segments 16 --mesh-rows 4 --output-interval 1)
names=(cotton_twill silk denim nylon polyester)
runs=()
for name in "${names[@]}"; do
  "$sartor" run "$case" "${coarse[@]}" --fabric "$fabrics/${name}_x10.yaml" \
    --output "$work/$name" > "$work/$name.log"
  runs+=("$work/$name")
done
labels=$(IFS=,; echo "${names[*]}")
"$python" "$postproc" twist "${runs[@]}" --labels "$labels" --json "$work/twist.json"
"$python" - "$work/twist.json" "$(dirname "$0")" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[2])
from experiment_checks import unfinished
runs = {r["label"]: r for r in json.load(open(sys.argv[1]))["runs"]}
failures = unfinished(runs.values())
strain = {name: r["residual_nonelastic_strain"] for name, r in runs.items()}
failures += [f"{name}: no residual non-elastic strain ({value})"
             for name, value in strain.items() if not value > 0.0]
if not strain["cotton_twill"] > 1.5 * strain["nylon"]:
    failures.append(f"cotton twill {strain['cotton_twill']:.4g} is not 1.5 x nylon {strain['nylon']:.4g}")
if failures:
    sys.exit("\n".join(failures))
PY
