#!/usr/bin/env bash
# The fabric.yaml written by `sartor fit` feeds `sartor creep --fabric`:
#
#   fit_to_creep.sh SARTOR FITDIR WORKDIR
#
# FITDIR is the output folder of a fit (synth_fit_roundtrip.sh leaves one).
# Checks that creep reads the fitted parameters exactly and that its strain
# history obeys the closed-form creep test with those parameters.
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR FITDIR WORKDIR" >&2; exit 2; }
sartor=$1 fitdir=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
[ -s "$fitdir/fabric.yaml" ] || { echo "fit_to_creep: $fitdir/fabric.yaml is missing" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"

"$sartor" creep --fabric "$fitdir/fabric.yaml" --no-plot --output "$work/creep"
# a direction the fit did not measure is an error naming it
if "$sartor" creep --fabric "$fitdir/fabric.yaml:weft" --no-plot --output "$work/weft" \
     > "$work/weft.log" 2>&1; then
  echo "fit_to_creep: the fitted fabric has no weft, but creep accepted it" >&2; exit 1
fi
grep -q "has no weft parameters" "$work/weft.log" || { cat "$work/weft.log" >&2; exit 1; }

# Fitted parameters, in the order check_creep_csv.sh takes them.
params=$("$python" - "$fitdir" "$work" <<'PY'
import json, sys
fitdir, work = sys.argv[1:]
p = {k: v["value"] for k, v in json.load(open(f"{fitdir}/fit.json"))["parameters"].items()}
summary = json.load(open(f"{work}/creep/summary.json"))
failures = []
runs = summary["runs"]
if len(runs) != 1 or runs[0]["name"] != "synth:warp" or runs[0]["csv"] != "creep.csv":
    failures.append(f"runs: {[(r['name'], r['csv']) for r in runs]}")
got = runs[0]["parameters"]
for key in ("E_N_per_m", "alpha", "lambda_load_per_s", "lambda_unload_per_s"):
    if got[key] != p[key]:
        failures.append(f"{key}: creep used {got[key]}, fit.json has {p[key]}")
if got["elastic"] != {"modulus_N_per_m": p["elastic_modulus_N_per_m"]}:
    failures.append(f"elastic: {got['elastic']} vs {p['elastic_modulus_N_per_m']}")
if not runs[0]["source"].startswith("sartor fit of "):
    failures.append(f"source: {runs[0]['source']}")
if failures:
    sys.exit("fit_to_creep: " + "; ".join(failures))
print(p["elastic_modulus_N_per_m"], p["E_N_per_m"], p["alpha"], p["lambda_load_per_s"],
      p["lambda_unload_per_s"])
PY
)
read -r K E alpha ll lu <<< "$params"
bash "$here/check_creep_csv.sh" "$work/creep/creep.csv" 2451.6625 "$K" "$E" "$alpha" "$ll" "$lu" 3600 7200
