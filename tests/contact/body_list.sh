#!/usr/bin/env bash
# Bodies are an indexed list: --body, --body2, ... --body99, gaps allowed. A
# small sheet falls onto a floor given as --body12, past a plane far below
# (--body) and a sphere above (--body3): the bodies are reported in index
# order, and the floor alone carries the sheet's weight (density x area x g).
#   body_list.sh SARTOR SMALL_SHEET.yaml WORKDIR
set -euo pipefail
sartor=$1 sheet=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$sheet" --mesh-width 1 --mesh-height 0.5 \
  --density 0.2 --gravity 0,0,-9.80665 \
  --body "plane point=0,0,-5 normal=0,0,1 name=deep" \
  --body3 "sphere center=0,0,5 radius=0.1 name=above" \
  --body12 "plane point=0,0,-0.05 normal=0,0,1 mu=0.3 name=floor" \
  --no-plot --output "$work/sheet" > "$work/sheet.log"
/usr/bin/python3 - "$work/sheet/summary.json" <<'PY'
import json, sys
bodies = json.load(open(sys.argv[1]))["contact"]["bodies"]
names = [b["body"].split(":")[0] for b in bodies]
assert names == ["deep", "above", "floor"], names
weight = 0.2 * 1.0 * 0.5 * 9.80665
lift = [b["reaction_N"][2] for b in bodies]
assert abs(lift[2] - weight) < 1e-6 * weight, (lift, weight)
assert lift[0] == 0.0 and lift[1] == 0.0, lift
print(f"bodies {names}; the floor carries {lift[2]:.6f} N of {weight:.6f} N")
PY
