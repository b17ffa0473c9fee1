#!/usr/bin/env bash
# `sartor fabrics`: the ten Table 5.1 parameter sets, elastic modulus 2E.
#
#   fabrics_list.sh SARTOR
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: $0 SARTOR" >&2; exit 2; }
sartor=$1
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
table=$("$sartor" fabrics)
json=$("$sartor" fabrics --json)
echo "$table"
grep -Eq '^cotton_twill:warp +32600 +0\.897 +0\.0886 +0\.002 +65200$' <<< "$table" \
  || { echo "fabrics_list: the table row of cotton_twill:warp is wrong" >&2; exit 1; }
grep -q 'elastic: assumed 2E (not in the thesis)' <<< "$table" \
  || { echo "fabrics_list: the table does not state the 2E assumption" >&2; exit 1; }

"$python" - <<PY
import json, sys
listed = json.loads('''$json''')
# thesis Table 5.1: E (N/m), alpha, lambda_load (1/s), lambda_unload (1/s)
table = {
    "cotton_twill:warp": (32600, 0.897, 0.0886, 0.00200),
    "cotton_twill:weft": (14100, 0.873, 0.0275, 0.00243),
    "silk:warp": (54000, 0.742, 0.0572, 0.00157),
    "silk:weft": (21600, 0.794, 0.311, 0.00190),
    "denim:warp": (25600, 0.667, 0.0331, 0.0147),
    "denim:weft": (42700, 0.728, 0.0540, 0.00310),
    "nylon:warp": (49600, 0.729, 0.0594, 0.00534),
    "nylon:weft": (30800, 0.705, 0.0376, 0.0598),
    "polyester:warp": (80400, 0.674, 0.00508, 0.00197),
    "polyester:weft": (10700, 0.645, 0.0227, 0.00870),
}
got = {p["name"]: (p["E_N_per_m"], p["alpha"], p["lambda_load_per_s"], p["lambda_unload_per_s"])
       for p in listed}
failures = []
if [p["name"] for p in listed] != list(table):
    failures.append(f"names {[p['name'] for p in listed]}")
for name, want in table.items():
    if got.get(name) != want:
        failures.append(f"{name}: {got.get(name)}, Table 5.1 has {want}")
for p in listed:
    if p["elastic_modulus_N_per_m"] != 2 * p["E_N_per_m"]:
        failures.append(f"{p['name']}: elastic modulus {p['elastic_modulus_N_per_m']} is not 2E")
if failures:
    sys.exit("fabrics_list: FAILED\n  " + "\n  ".join(failures))
print("fabrics_list: ten Table 5.1 sets, elastic modulus 2E")
PY
