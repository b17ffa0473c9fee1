#!/usr/bin/env bash
# drape's echoed options (petsc_options.txt) re-run the same job: a short
# drape of the skirt, run again from `-options_file petsc_options.txt`, must
# write the same final.obj. (The --body value has spaces and must come back
# quoted; drape's own seams file must not come back as --seams-file.)
#
#   drape_options_echo.sh SARTOR PATTERN.json WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR PATTERN.json WORKDIR" >&2; exit 2; }
sartor=$1 pattern=$2 work=$3
rm -rf "$work" && mkdir -p "$work"

"$sartor" drape "$pattern" --time-end 0.02 --sewing-time 0.01 --edge-length 0.08 -settle false \
  --no-plot --output "$work/first" > "$work/first.log"
grep -Eq '^-(contact_)?body "mannequin' "$work/first/petsc_options.txt" ||
  { echo "drape_options_echo: -body is not quoted" >&2; exit 1; }
"$sartor" drape "$pattern" -options_file "$work/first/petsc_options.txt" --output "$work/again" \
  > "$work/again.log"
cmp "$work/first/final.obj" "$work/again/final.obj" ||
  { echo "drape_options_echo: the re-run drew another garment" >&2; exit 1; }
echo "drape_options_echo: the echoed options re-ran the same drape"
