#!/usr/bin/env bash
# `sartor creep --tension-history`: rows at every breakpoint (both sides of a
# jump), linear tension in between, and strains that match the creep law in
# closed form where it has one.
#
#   tension_history.sh SARTOR HISTORY.csv WORKDIR
#
# HISTORY is tests/cli/data/history_ramp_hold.csv: 0 -> 2000 N/m over 60 s,
# hold to 1800 s, jump to 500 N/m, hold to 3600 s, release, recover to 7200 s.
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR HISTORY.csv WORKDIR" >&2; exit 2; }
sartor=$1 history=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"

"$sartor" creep --fabric cotton_twill:warp --tension-history "$history" --no-plot \
  --output "$work/log"
"$sartor" creep --fabric cotton_twill:warp --tension-history "$history" --no-plot \
  --sample-interval 600 --output "$work/uniform"

"$python" - "$work" "$history" <<'PY'
import csv, json, math, sys
work, history = sys.argv[1:]
E, alpha, ll, lu, K = 32600.0, 0.897, 0.0886, 0.002, 65200.0  # cotton_twill:warp, K = 2E
failures = []
def close(a, b, rtol=1e-9):
    return abs(a - b) <= rtol * abs(b) + 1e-300

def rows_of(folder):
    with open(f"{work}/{folder}/creep.csv") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]

breakpoints = [(0, 0), (60, 2000), (1800, 2000), (1800, 500), (3600, 500), (3600, 0), (7200, 0)]
for folder in ("log", "uniform"):
    rows = rows_of(folder)
    pairs = [(r["time_s"], r["tension_N_per_m"]) for r in rows]
    at_breakpoints = [p for p in pairs if p in breakpoints]
    if at_breakpoints != breakpoints:
        failures.append(f"{folder}: breakpoint rows {at_breakpoints}")
    previous = None
    for r in rows:
        t, s = r["time_s"], r["tension_N_per_m"]
        v, p, e, total = r["strain_viscoelastic"], r["strain_permanent"], r["strain_elastic"], r["strain_total"]
        if not close(e + (v + p), total, 1e-14):
            failures.append(f"{folder}: t={t}: parts do not add up"); break
        if not close(e, s / K * (1 + v + p), 1e-12):
            failures.append(f"{folder}: t={t}: elastic {e} != tension/K (1+eps_v+eps_p)"); break
        if 0 < t < 60 and not close(s, 2000 * t / 60, 1e-12):
            failures.append(f"{folder}: t={t}: tension {s} is not on the ramp"); break
        if previous and (t < previous["time_s"] or p < previous["strain_permanent"]):
            failures.append(f"{folder}: t={t}: time or permanent strain decreases"); break
        previous = r
    # Closed forms: saturated at the end of the hold (1740 s at lambda_l = 0.0886/s) ...
    hold = next(r for r in rows if r["time_s"] == 1800 and r["tension_N_per_m"] == 2000)
    v1800, p1800 = (1 - alpha) * 2000 / E, alpha * 2000 / E
    if not (close(hold["strain_viscoelastic"], v1800) and close(hold["strain_permanent"], p1800)):
        failures.append(f"{folder}: end of hold {hold}, expected eps_v {v1800} eps_p {p1800}")
    # ... then eps_v relaxes towards (1-alpha) 500/E at lambda_u, eps_p stays ...
    low = next(r for r in rows if r["time_s"] == 3600 and r["tension_N_per_m"] == 500)
    target = (1 - alpha) * 500 / E
    v3600 = target + (v1800 - target) * math.exp(-lu * 1800)
    if not (close(low["strain_viscoelastic"], v3600) and close(low["strain_permanent"], p1800)):
        failures.append(f"{folder}: t=3600 loaded {low}, expected eps_v {v3600} eps_p {p1800}")
    # ... and recovers towards 0 after the release.
    end = rows[-1]
    v7200 = v3600 * math.exp(-lu * 3600)
    if not (end["time_s"] == 7200 and close(end["strain_viscoelastic"], v7200)
            and close(end["strain_permanent"], p1800) and end["strain_elastic"] == 0):
        failures.append(f"{folder}: last row {end}, expected eps_v {v7200} eps_p {p1800}")

uniform_times = [r["time_s"] for r in rows_of("uniform")]
want = sorted([0, 60, 1800, 1800, 3600, 3600] + [600.0 * k for k in range(1, 13) if k not in (3, 6)])
if uniform_times != want:
    failures.append(f"uniform: times {uniform_times}, expected {want}")

summary = json.load(open(f"{work}/log/summary.json"))
if summary["load"] != {"kind": "history", "file": history}:
    failures.append(f"summary load {summary['load']}")
run = summary["runs"][0]
if "end_of_loading" in run or "saturation_creep_strain" in run:
    failures.append("a history run has end_of_loading/saturation_creep_strain")
if run["rows"] != len(rows_of("log")):
    failures.append(f"summary rows {run['rows']} != CSV rows")
if failures:
    sys.exit("tension_history: FAILED\n  " + "\n  ".join(failures))
print(f"tension_history: {len(rows_of('log'))} log-spaced and {len(uniform_times)} uniform rows OK")
PY
