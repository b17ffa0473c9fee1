#!/usr/bin/env bash
# A fit of a file whose name YAML would misread ("a: b #3") writes a
# fabric.yaml that sartor creep reads back under that very name.
#   fit_awkward_name.sh SARTOR WORKDIR
set -euo pipefail
sartor=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
data="$work/a: b #3.csv"
"$sartor" synth --fabric nylon:weft --samples 2000 --noise 0 --output "$data" > /dev/null
"$sartor" fit "$data" --no-plot --output "$work/fit" > /dev/null
"$sartor" creep --fabric "$work/fit/fabric.yaml" --no-plot --output "$work/creep" > /dev/null
grep -q '"name": "a: b #3:warp"' "$work/creep/summary.json" ||
  { echo "fitted fabric not read back under its name:" >&2; grep '"name"' "$work/creep/summary.json" >&2; exit 1; }
