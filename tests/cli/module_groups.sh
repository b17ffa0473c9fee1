#!/usr/bin/env bash
# Options under their modules' prefixes (src/app/cli.hpp): a case written in
# module groups (mesh: kind: ..., material: density: ...) is the same case as
# the flat one with the old names; the command line overrides a case file's
# value given by the option's other name; a file giving both names
# different values is refused, naming both.
#
#   module_groups.sh SARTOR FLAT.yaml GROUPED.yaml TWICE.yaml WORKDIR
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: $0 SARTOR FLAT.yaml GROUPED.yaml TWICE.yaml WORKDIR" >&2; exit 2; }
sartor=$1 flat=$2 grouped=$3 twice=$4 work=$5
python=/usr/bin/python3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "module_groups: $*" >&2; exit 1; }

"$sartor" run "$flat" --no-plot --output "$work/flat" > "$work/flat.log"
"$sartor" run "$grouped" --no-plot --output "$work/grouped" > "$work/grouped.log"
grep -q "was not used" "$work/grouped.log" && fail "an option of the grouped case was unused"
cmp -s "$work/flat/final.obj" "$work/grouped/final.obj" || fail "the grouped case drew another sheet"
"$sartor" run "$flat" --material-density 0.4 --no-plot --output "$work/heavier" > /dev/null
"$python" - "$work" <<'PY' || exit 1
import json, sys
work = sys.argv[1]
flat = json.load(open(f"{work}/flat/summary.json"))["options"]
heavier = json.load(open(f"{work}/heavier/summary.json"))["options"]
assert flat["material-density"] == "0.2" and "density" not in flat, flat
assert flat["mesh-kind"] == "rectangle", flat
assert heavier["material-density"] == "0.4", heavier
PY
cmp -s "$work/flat/final.obj" "$work/heavier/final.obj" && fail "--material-density did not override density:"
set +e
"$sartor" run "$flat" -options_file_yaml "$twice" --no-plot --output "$work/twice" 2> "$work/twice.err"
status=$?
set -e
[ "$status" -eq 2 ] || fail "both names in files: exit $status, expected 2"
grep -q "option --material-density is given twice.*--density" "$work/twice.err" ||
  fail "both names in files: $(cat "$work/twice.err")"
echo "module_groups: grouped and flat cases agree; the command line wins; a clash is refused"
