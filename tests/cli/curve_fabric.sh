#!/usr/bin/env bash
# A fabric file with both directions: a piecewise-linear elastic_curve along
# the warp and an elastic_modulus along the weft.
#
#   curve_fabric.sh SARTOR FABRIC.yaml WORKDIR
#
# FABRIC is tests/cli/data/curve_fabric.yaml (cotton-twill creep parameters).
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR FABRIC.yaml WORKDIR" >&2; exit 2; }
sartor=$1 fabric=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"

"$sartor" creep --fabric "$fabric" --no-plot --output "$work/creep"
"$sartor" synth --fabric "$fabric:warp" --samples 100 --noise 0 --output "$work/synth.csv"

"$python" - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
failures = []
summary = json.load(open(f"{work}/creep/summary.json"))
runs = {r["name"]: r for r in summary["runs"]}
if sorted(runs) != ["curvy_twill:warp", "curvy_twill:weft"]:
    failures.append(f"runs {sorted(runs)}")
warp, weft = runs["curvy_twill:warp"], runs["curvy_twill:weft"]
if warp["csv"] != "creep_curvy_twill_warp.csv" or weft["csv"] != "creep_curvy_twill_weft.csv":
    failures.append(f"csv names {warp['csv']} {weft['csv']}")
if warp["source"] != "sartor CLI test fixture":
    failures.append(f"source {warp['source']}")
curve = [[0.0, 0.0], [0.01, 400.0], [0.03, 1600.0], [0.06, 5000.0]]
if warp["parameters"]["elastic"] != {"curve_strain_tension": curve}:
    failures.append(f"warp elastic {warp['parameters']['elastic']}")
if weft["parameters"]["elastic"] != {"modulus_N_per_m": 30000.0}:
    failures.append(f"weft elastic {weft['parameters']['elastic']}")

def strain_at(tension):  # inverse of the curve, last segment extended
    for (e0, s0), (e1, s1) in zip(curve, curve[1:]):
        if tension <= s1 or (e1, s1) == tuple(curve[-1]):
            return e0 + (tension - s0) * (e1 - e0) / (s1 - s0)

with open(f"{work}/creep/creep_curvy_twill_warp.csv") as f:
    for r in csv.DictReader(f):
        r = {k: float(v) for k, v in r.items()}
        want = strain_at(r["tension_N_per_m"]) * (1 + r["strain_viscoelastic"] + r["strain_permanent"])
        if abs(r["strain_elastic"] - want) > 1e-12 * max(want, 1e-300):
            failures.append(f"warp t={r['time_s']}: elastic {r['strain_elastic']}, expected {want}")
            break

# synth uses the secant modulus of the curve at the test tension.
sigma = 196.133 / 0.08
with open(f"{work}/synth.csv") as f:
    line = next(l for l in f if l.startswith("# parameters:"))
secant = float(line.split("elastic_modulus_N_per_m=")[1].split()[0])
if abs(secant - sigma / strain_at(sigma)) > 1e-9 * secant:
    failures.append(f"synth secant modulus {secant}, expected {sigma / strain_at(sigma)}")
if failures:
    sys.exit("curve_fabric: FAILED\n  " + "\n  ".join(failures))
print(f"curve_fabric: curve honoured; secant modulus at {sigma} N/m is {secant} N/m")
PY
# the weft direction is linear: the closed form applies (K = 30000 N/m)
bash "$here/check_creep_csv.sh" "$work/creep/creep_curvy_twill_weft.csv" 2451.6625 30000 14100 \
  0.873 0.0275 0.00243 3600 7200
