#!/usr/bin/env bash
# synth -> fit round trip on noise-free data: the fit must recover the
# generating parameters to 1e-6 relative.
#
#   synth_fit_roundtrip.sh SARTOR WORKDIR FABRIC:DIR [LAUNCHER...]
#
# LAUNCHER (e.g. mpiexec -n 2) runs the fit; the synthetic file is written
# serially. Leaves WORKDIR/synth.csv and WORKDIR/fit/ for later tests.
# Needs /usr/bin/python3 (standard library only); fails without it (./dev deps installs it).
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 SARTOR WORKDIR FABRIC:DIR [LAUNCHER...]" >&2; exit 2; }
sartor=$1 work=$2 fabric=$3
shift 3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"

"$sartor" synth --fabric "$fabric" --samples 2000 --noise 0 --output "$work/synth.csv"
"$sartor" fabrics --json > "$work/fabrics.json"
ranks=1
if [ $# -gt 0 ]; then
  ranks=$(printf '%s\n' "$@" | awk 'prev == "-n" || prev == "-np" { print; exit } { prev = $0 }')
  ranks=${ranks:-1}
fi
"$@" "$sartor" fit "$work/synth.csv" --no-plot --output "$work/fit" | tee "$work/fit.log"

"$python" - "$work" "$fabric" "$ranks" <<'PY'
import json, math, sys

work, fabric, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3])
failures = []

def check(ok, what):
    if not ok:
        failures.append(what)

def rel(a, b):
    return abs(a - b) / abs(b)

# The generating parameters, from the synthetic file's header ...
header = {}
with open(f"{work}/synth.csv") as f:
    lines = f.read().splitlines()
comments = [l for l in lines if l.startswith("#")]
for line in comments:
    if line.startswith("# parameters:"):
        header = {k: float(v) for k, v in (kv.split("=") for kv in line.split(":", 1)[1].split())}
check(set(header) == {"elastic_modulus_N_per_m", "E_N_per_m", "alpha", "lambda_load_per_s",
                      "lambda_unload_per_s"}, f"synth header parameters: {header}")
# ... which must be the preset's (creep: Table 5.1; elastic modulus 2E).
preset = {p["name"]: p for p in json.load(open(f"{work}/fabrics.json"))}[fabric]
for key in ("E_N_per_m", "alpha", "lambda_load_per_s", "lambda_unload_per_s"):
    check(header.get(key) == preset[key], f"synth header {key} {header.get(key)} != preset {preset[key]}")
check(header.get("elastic_modulus_N_per_m") == 2 * preset["E_N_per_m"],
      "synth elastic modulus is not 2E")

fit = json.load(open(f"{work}/fit/fit.json"))
check(fit["command"] == "fit", "fit.json command")
check(fit["mpi_ranks"] == ranks, f"mpi_ranks {fit['mpi_ranks']} != {ranks}")
check(fit["solver"]["converged"] is True, f"not converged: {fit['solver']}")
inp = fit["input"]
check(inp["samples"] == 2000, f"samples {inp['samples']}")
check(rel(inp["tension_N_per_m"], 196.133 / 0.08) < 1e-12, f"tension {inp['tension_N_per_m']}")
check(inp["load_time_s"] == 0.0 and inp["unload_time_s"] == 3600.0,
      f"load/unload times {inp['load_time_s']} {inp['unload_time_s']}")
check(inp["end_time_s"] == 1999 * 7200 / 2000, f"end time {inp['end_time_s']}")
check(inp["tension_from"].startswith("mean of the tension column"), inp["tension_from"])
worst = 0.0
for key, want in header.items():
    got = fit["parameters"][key]["value"]
    worst = max(worst, rel(got, want))
    check(rel(got, want) < 1e-6, f"{key}: fitted {got}, generated with {want}")
    lo, hi = fit["parameters"][key]["ci_low"], fit["parameters"][key]["ci_high"]
    check(lo <= got <= hi, f"{key}: value outside its interval [{lo}, {hi}]")
check(fit["goodness"]["rmse"] < 1e-9, f"rmse {fit['goodness']['rmse']} on exact data")
check(fit["goodness"]["degrees_of_freedom"] == 1995, "degrees of freedom")
check(fit["saturation"]["warnings"] == [], f"warnings {fit['saturation']['warnings']}")
check(fit["correlation"]["order"] == ["elastic_modulus_N_per_m", "E_N_per_m", "alpha",
                                      "lambda_load_per_s", "lambda_unload_per_s"], "correlation order")

# fit.csv: one row per sample, residual = measured - fit, phases 1 then 2, the
# tension of the test while loaded and 0 after.
with open(f"{work}/fit/fit.csv") as f:
    rows = f.read().splitlines()
check(rows[0] == "time_s,strain_measured,strain_fit,residual,phase,tension_N_per_m",
      f"fit.csv header {rows[0]}")
check(len(rows) == 2001, f"fit.csv has {len(rows) - 1} rows")
for row in rows[1:]:
    t, measured, model, residual, phase, tension = row.split(",")
    t, measured, model, residual, tension = map(float, (t, measured, model, residual, tension))
    if abs(residual - (measured - model)) > 1e-15 or abs(residual) > 1e-8 or \
       phase != ("1" if t < 3600 else "2") or (tension > 0) != (t < 3600):
        failures.append(f"fit.csv row {row}")
        break

# fabric.yaml carries the fitted values, shortest round-trip text.
values = {}
with open(f"{work}/fit/fabric.yaml") as f:
    for line in f:
        line = line.split("#", 1)[0].strip()
        if ":" in line:
            key, value = (s.strip() for s in line.split(":", 1))
            values[key] = value
check(values.get("name") == "synth", f"fabric.yaml name {values.get('name')}")
check("warp" in values, "fabric.yaml has no warp section")
names = {"E": "E_N_per_m", "alpha": "alpha", "lambda_load": "lambda_load_per_s",
         "lambda_unload": "lambda_unload_per_s", "elastic_modulus": "elastic_modulus_N_per_m"}
for yaml_key, json_key in names.items():
    check(float(values.get(yaml_key, "nan")) == fit["parameters"][json_key]["value"],
          f"fabric.yaml {yaml_key} {values.get(yaml_key)} != fit.json")

if failures:
    print("synth_fit_roundtrip: FAILED\n  " + "\n  ".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"synth_fit_roundtrip: {fabric} on {ranks} rank(s): parameters recovered to {worst:.2e}")
PY
