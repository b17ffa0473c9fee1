#!/bin/bash
# bending_psd_methods_agree.sh SARTOR CASE OUT: the patch model's two PSD
# Hessians (--bending-psd-method gauss-newton and eigenvalues) only steer the
# minimiser: the cantilever strip (a unique equilibrium) must end at the same
# tip deflection, to 1e-7 of it (the runs measured 1.4e-10 apart), both
# certified, each summary naming its method, by different paths.
set -euo pipefail
sartor=$1 case=$2 out=$3
python=/usr/bin/python3
for method in gauss-newton eigenvalues; do
  "$sartor" run "$case" --bending-psd --bending-psd-method "$method" --no-plot \
    --output "$out/$method" > "$out/$method.log" 2>&1 || { cat "$out/$method.log"; exit 1; }
done
"$python" - "$out" <<'PY'
import json, sys
out = sys.argv[1]
runs = {m: json.load(open("%s/%s/summary.json" % (out, m))) for m in ("gauss-newton", "eigenvalues")}
for method, summary in runs.items():
    assert summary["options"]["material-bending-psd-method"] == method, method
    assert summary["certificate"]["verdict"] == "certified", method
a, b = (runs[m]["max_displacement_m"] for m in ("gauss-newton", "eigenvalues"))
print("tip deflection: gauss-newton %.12g m, eigenvalues %.12g m" % (a, b))
assert abs(a - b) <= 1e-7 * abs(b), "the two Hessians' equilibria differ"
# Different Hessians, different paths: bit-equal final residuals would mean
# the option changed nothing.
residuals = [runs[m]["solver"]["final_residual_norm"] for m in runs]
assert residuals[0] != residuals[1], "both methods took the same path"
PY
