#!/bin/bash
# A wear case worn with each of the five Table 5.1 fabrics, one after the
# other, then the plot and pictures of postproc/plot_wear.py (docs/wear.md).
# Run from the repository root:
#   cases/wear/run_fabrics.sh PATTERN CASE NAME [SARTOR] [OUT]
# e.g. cases/wear/run_fabrics.sh cases/patterns/skirt.json cases/wear/skirt_8h.yaml skirt
# writes OUT/NAME_FABRIC (default OUT: out/wear), OUT/NAME_wear.png and
# OUT/NAME_FABRIC.png (the garment after its take-off; STATE=wear: in its
# last worn state, on the body). FABRICS="silk denim" runs only those.
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,9p' "$0" >&2
  exit 2
fi
pattern=$1 case=$2 name=$3
sartor=${4:-build/bin/sartor}
out=${5:-out/wear}
fabrics=${FABRICS:-cotton_twill silk denim nylon polyester}
for fabric in $fabrics; do
  "$sartor" drape "$pattern" -options_file_yaml "$case" \
    --fabric "$fabric" --output "$out/${name}_$fabric" --no-plot
done
runs=()
for fabric in $fabrics; do runs+=("$out/${name}_$fabric"); done
postproc/plot_wear.py "${runs[@]}" --output "$out/${name}_wear.png" --pictures "$out/$name" \
  --state "${STATE:-takeoff}"
