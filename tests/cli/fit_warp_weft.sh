#!/usr/bin/env bash
# sartor fit WARP.csv --weft-data WEFT.csv: both directions of one fabric in
# one run. Each direction's fit.json must put the generating parameters (the
# '# parameters:' line sartor synth writes) within 5 standard errors, and
# fabric.yaml must hold both directions with the fitted values.
#
#   fit_warp_weft.sh SARTOR WORKDIR FABRIC
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR WORKDIR FABRIC" >&2; exit 2; }
sartor=$1 work=$2 fabric=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
"$python" -c "import yaml" 2>/dev/null || { echo "error: python3-yaml missing (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$sartor" synth --fabric "$fabric:warp" --samples 5000 --seed 21 --output "$work/warp.csv"
"$sartor" synth --fabric "$fabric:weft" --samples 5000 --seed 22 --output "$work/weft.csv"
"$sartor" fit "$work/warp.csv" --weft-data "$work/weft.csv" --bootstrap 0 --no-plot \
  --name "$fabric" --output "$work/fit"
"$python" - "$work" <<'PY'
import json, sys, yaml
work = sys.argv[1]
fabric = yaml.safe_load(open(f"{work}/fit/fabric.yaml"))
failures = []
yaml_keys = {"E_N_per_m": "E", "alpha": "alpha", "lambda_load_per_s": "lambda_load",
             "lambda_unload_per_s": "lambda_unload", "elastic_modulus_N_per_m": "elastic_modulus"}
for direction, report in (("warp", f"{work}/fit/fit.json"), ("weft", f"{work}/fit/weft/fit.json")):
    with open(f"{work}/{direction}.csv") as f:
        line = next(l for l in f if l.startswith("# parameters:"))
    truth = {k: float(v) for k, v in (kv.split("=") for kv in line.split(":", 1)[1].split())}
    fit = json.load(open(report))
    for key, want in truth.items():
        p = fit["parameters"][key]
        if abs(p["value"] - want) > 5 * p["std_error"]:
            failures.append(f"{direction} {key}: {p['value']} +- {p['std_error']}, generated {want}")
        if abs(fabric[direction][yaml_keys[key]] - p["value"]) > 1e-12 * abs(p["value"]):
            failures.append(f"fabric.yaml {direction} {key} differs from fit.json")
if failures:
    sys.exit("fit_warp_weft: FAILED\n  " + "\n  ".join(failures))
print("fit_warp_weft: both directions within 5 standard errors, fabric.yaml has both")
PY
