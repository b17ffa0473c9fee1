#!/usr/bin/env bash
# `-options_file_yaml CASE` sets application options (keys without dashes):
#
#   options_file.sh SARTOR CASE.yaml WORKDIR
#
# CASE is tests/cli/data/case_silk_weft.yaml: silk:weft, 50 N on 0.05 m,
# 600 s loading, 1200 s recovery, no plot. Checks that summary.json and the
# CSV follow the case, and that options after the file override it.
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASE.yaml WORKDIR" >&2; exit 2; }
sartor=$1 case_file=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"

"$sartor" creep -options_file_yaml "$case_file" --output "$work/case" | tee "$work/case.log"
# Options are applied in command-line order (PETSc): an option after the
# file overrides the file, one before it is overridden by the file.
"$sartor" creep -options_file_yaml "$case_file" --load-duration 900 --output "$work/override" \
  | tee "$work/override.log"
"$sartor" creep --load-duration 900 -options_file_yaml "$case_file" --output "$work/before" \
  | tee "$work/before.log"
if grep -q "was not used" "$work/case.log" "$work/override.log" "$work/before.log"; then
  echo "options_file: an option of the case was reported unused" >&2; exit 1
fi

"$python" - "$work" <<'PY'
import json, os, sys
work = sys.argv[1]
failures = []
def expect(summary, what, duration, end):
    load = summary["load"]
    want = {"kind": "creep_recovery", "tension_N_per_m": 1000.0, "force_N": 50.0,
            "width_m": 0.05, "load_duration_s": duration, "recovery_duration_s": 1200.0}
    if load != want:
        failures.append(f"{what}: load {load}, expected {want}")
    runs = summary["runs"]
    if [r["name"] for r in runs] != ["silk:weft"]:
        failures.append(f"{what}: runs {[r['name'] for r in runs]}")
    elif runs[0]["final"]["time_s"] != end:
        failures.append(f"{what}: final time {runs[0]['final']['time_s']}, expected {end}")
    options = summary["options"]
    if options.get("fabric") != "silk:weft" or options.get("no-plot") != "true":
        failures.append(f"{what}: options {options}")
    if options.get("load-duration") != ("600" if duration == 600 else "900"):
        failures.append(f"{what}: options load-duration {options.get('load-duration')}")
for name, duration, end in (("case", 600.0, 1800.0), ("override", 900.0, 2100.0),
                            ("before", 600.0, 1800.0)):
    expect(json.load(open(f"{work}/{name}/summary.json")), name, duration, end)
    if os.path.exists(f"{work}/{name}/creep.png"):
        failures.append(f"{name}: no_plot: true in the case, but creep.png was written")
if failures:
    sys.exit("options_file: FAILED\n  " + "\n  ".join(failures))
print("options_file: summary.json follows the case file and the command-line override")
PY
# silk weft (Table 5.1, elastic modulus 2E), 1000 N/m for 600 s, until 1800 s
bash "$here/check_creep_csv.sh" "$work/case/creep.csv" 1000 43200 21600 0.794 0.311 0.0019 600 1800
