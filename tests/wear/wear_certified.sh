#!/usr/bin/env bash
# The skirt worn 6 s (5 steps) and taken off: every wear state is certified
# (docs/wear.md), with drape's contact rounds within each step (the default
# --wear-contact-rounds 30: friction anchors updated until consistent). With
# the anchors lagged by a step (--wear-contact-rounds 0) the states are not in
# equilibrium with the anchors they end with, and the run says so. The
# permanent dome height of every worn state (wear.csv) and its plot.
#   wear_certified.sh SARTOR PROJECT_DIR WORKDIR
set -euo pipefail
sartor=$1 project=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
args=("$project/cases/patterns/skirt.json" --edge-length 0.08 --no-plot --take-off-times 6
  --recovery-time 10 --wear-first-step 2 --creep-tolerance 1e-2 -snes_max_it 2000)
"$sartor" drape "${args[@]}" --wear-time 6 --output "$work/rounds" > "$work/rounds.log" 2>&1 ||
  { cat "$work/rounds.log" >&2; echo "the wear failed" >&2; exit 1; }
cat "$work/rounds/wear.csv"
# Column 11 of wear.csv is the state's certificate, column 7 of takeoff.csv whether it is certified.
awk -F, 'NR > 1 && $11 != "certified" { print "wear state at t = " $1 " s: " $11; bad = 1 }
  END { if (NR < 5) { print "fewer than 4 wear steps"; bad = 1 }; exit bad }' "$work/rounds/wear.csv" >&2
awk -F, 'NR > 1 && $7 != 1 { print "the take-off at " $1 " s is not certified"; bad = 1 }
  END { if (NR != 2) { print "not one take-off"; bad = 1 }; exit bad }' "$work/rounds/takeoff.csv" >&2
if grep -q "not certified" "$work/rounds.log"; then
  cat "$work/rounds.log" >&2
  exit 1
fi
# Column 12 of wear.csv, the worn state's permanent dome height, never falls
# (permanent strain never shrinks) and grows over the wear; the plot draws it
# and the pictures the last worn state.
awk -F, 'NR == 1 && $12 != "dome_height_m" { print "wear.csv has no dome_height_m"; bad = 1 }
  NR > 2 && $12 < last - 1e-12 { print "the dome height fell at t = " $1 " s"; bad = 1 }
  NR > 1 { last = $12 } END { if (!(last > 0)) { print "no dome after the wear"; bad = 1 }; exit bad }' \
  "$work/rounds/wear.csv" >&2
/usr/bin/python3 "$project/postproc/plot_wear.py" "$work/rounds" --output "$work/wear.png" \
  --pictures "$work/worn" --state wear
[ -s "$work/wear.png" ] && [ -s "$work/worn_cotton_twill.png" ] ||
  { echo "plot_wear.py drew nothing" >&2; exit 1; }

"$sartor" drape "${args[@]}" --wear-time 2 --take-off-times 2 --wear-contact-rounds 0 \
  --output "$work/lagged" > "$work/lagged.log" 2>&1 || { cat "$work/lagged.log" >&2; exit 1; }
grep -q "warning: 1 of 2 wear states are not certified, the first at t = 2 s: residual" \
  "$work/lagged.log" || { cat "$work/lagged.log" >&2; echo "no warning of the lagged state" >&2; exit 1; }
