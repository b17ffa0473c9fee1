#!/usr/bin/env bash
# Fits a noisy synthetic file and checks that the fit converged and that each
# generating parameter lies within 5 standard errors of its estimate.
#
#   fit_noisy.sh SARTOR WORKDIR DATA.csv          (a file written by sartor synth)
#   fit_noisy.sh SARTOR WORKDIR FABRIC:DIR SEED   (synthesised here: 7200 samples, SD 2e-4)
set -euo pipefail
[ $# -eq 3 ] || [ $# -eq 4 ] || { echo "usage: $0 SARTOR WORKDIR DATA.csv | FABRIC:DIR SEED" >&2; exit 2; }
sartor=$1 work=$2
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
if [ $# -eq 4 ]; then
  data=$work/synth.csv
  "$sartor" synth --fabric "$3" --samples 7200 --noise 2e-4 --seed "$4" --output "$data"
else
  data=$3
fi
status=0
"$sartor" fit "$data" --no-plot --output "$work/fit" || status=$?
"$python" - "$data" "$work/fit/fit.json" "$status" <<'PY'
import json, sys
data, report, status = sys.argv[1], sys.argv[2], int(sys.argv[3])
with open(data) as f:
    line = next((l for l in f if l.startswith("# parameters:")), None)
if line is None:
    sys.exit(f"fit_noisy: {data} has no '# parameters:' line (not written by sartor synth)")
truth = {k: float(v) for k, v in (kv.split("=") for kv in line.split(":", 1)[1].split())}
fit = json.load(open(report))
failures = []
if status != 0 or not fit["solver"]["converged"]:
    failures.append(f"exit status {status}, stopped on {fit['solver']['reason']}")
for key, want in truth.items():
    p = fit["parameters"][key]
    if abs(p["value"] - want) > 5 * p["std_error"]:
        failures.append(f"{key}: {p['value']} +- {p['std_error']}, generated with {want}")
if failures:
    sys.exit(f"fit_noisy: {data}: FAILED\n  " + "\n  ".join(failures))
print(f"fit_noisy: {data}: converged ({fit['solver']['reason']}), parameters within 5 standard errors")
PY
