#!/usr/bin/env bash
# `sartor creep --fabric X.yml` reads the file, however short its name.
#   creep_yml_fabric.sh SARTOR FABRIC.yml WORKDIR
set -euo pipefail
sartor=$1 fabric=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cp "$fabric" "$work/a.yml"
(cd "$work" && "$sartor" creep --fabric a.yml --no-plot --output out)
grep -q '"source"' "$work/out/summary.json"
grep -q "a.yml" "$work/out/summary.json" || { echo "summary.json does not name a.yml" >&2; exit 1; }
