#!/bin/bash
# The skirt of skirt_8h.yaml worn with each of the five Table 5.1 fabrics,
# then the plot and pictures (docs/wear.md). Run from the repository root:
#   cases/wear/run_skirt_fabrics.sh [build/bin/sartor] [out/wear]
set -euo pipefail
sartor=${1:-build/bin/sartor}
out=${2:-out/wear}
for fabric in cotton_twill silk denim nylon polyester; do
  "$sartor" drape cases/patterns/skirt.json -options_file_yaml cases/wear/skirt_8h.yaml \
    --fabric "$fabric" --output "$out/skirt_$fabric" --no-plot
done
postproc/plot_wear.py "$out"/skirt_* --output "$out/skirt_wear.png" --pictures "$out/skirt"
