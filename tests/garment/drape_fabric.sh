#!/usr/bin/env bash
# `sartor drape --fabric SPEC` puts one fabric on every panel instead of the
# pattern's own (the sample skirt is cotton twill): a short fall without the
# settle, checked in summary.json and in the run's options.
#
#   drape_fabric.sh SARTOR PATTERN OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR PATTERN OUT_DIR" >&2; exit 2; }
sartor=$1 pattern=$2 dir=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
grep -q '"fabric": "cotton_twill"' "$pattern"
"$sartor" drape "$pattern" --fabric silk --edge-length 0.08 --time-end 0.02 --sewing-time 0.01 \
  -settle false --no-plot --output "$dir" | tee "$dir.log"
grep -q "dynamics completed; equilibrium not checked without --settle" "$dir.log"
"$python" - "$dir" <<'PY'
import json, os, sys
s = json.load(open(os.path.join(sys.argv[1], "summary.json")))
assert s["fabrics"] == ["silk"], s["fabrics"]
assert s["dynamics"]["completed"], s["dynamics"]
assert not s["drape"]["equilibrium_checked"], s["drape"]
print("drape_fabric: every panel silk")
PY
