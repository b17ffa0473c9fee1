#!/usr/bin/env bash
# summary.json's end_of_loading must be the loaded state at the unload time
# (the CSV row at t = load_duration with the test tension).
#
#   summary_end_of_loading.sh SARTOR OUTDIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SARTOR OUTDIR" >&2; exit 2; }
sartor=$1 out=$2
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$out"
"$sartor" creep --fabric polyester:warp --load-duration 300 --recovery-duration 300 --no-plot \
  --output "$out"
"$python" - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
run = json.load(open(f"{out}/summary.json"))["runs"][0]
with open(f"{out}/creep.csv") as f:
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
loaded = next(r for r in rows if r["time_s"] == 300 and r["tension_N_per_m"] > 0)
if run["end_of_loading"] != loaded:
    sys.exit(f"summary_end_of_loading: end_of_loading is {run['end_of_loading']},\n"
             f"  but the loaded state at t = 300 s is {loaded}")
print("summary_end_of_loading: end_of_loading is the loaded row at t = 300 s")
PY
