#!/usr/bin/env bash
# Regenerates cases/import/freesewing/'s SVGs and measurement files from the
# pinned npm packages (tools/freesewing/generate.sh) and checks that every
# file is identical to the committed one. Skipped (exit 77) where the
# packages are not installed (`./dev deps` installs them where node >= 20).
#
#   freesewing_regen.sh REPOSITORY_ROOT OUT_DIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 REPOSITORY_ROOT OUT_DIR" >&2; exit 2; }
root=$1 dir=$2
if [ ! -d "$root/tools/freesewing/node_modules/@freesewing/core" ] || ! command -v node >/dev/null; then
  echo "skipped: tools/freesewing/node_modules or node missing (./dev deps installs them)"
  exit 77
fi
rm -rf "$dir"
mkdir -p "$dir"
"$root/tools/freesewing/generate.sh" "$dir"
count=0
for file in "$dir"/*; do
  cmp "$file" "$root/cases/import/freesewing/$(basename "$file")"
  count=$((count + 1))
done
[ "$count" -ge 3 ] || { echo "generate.sh wrote $count files, expected at least 3" >&2; exit 1; }
echo "$count regenerated files identical to cases/import/freesewing/"
