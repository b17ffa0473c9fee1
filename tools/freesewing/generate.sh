#!/bin/sh
# Regenerates the FreeSewing cases of cases/import/freesewing/ into DIR
# (default: that folder) from the npm packages pinned in package-lock.json
# (`./dev deps` or `npm ci` here first). A test (cli_import_freesewing_regen)
# runs it into a temporary folder and checks the files are identical.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/../../cases/import/freesewing}
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ]; then
  echo "usage: tools/freesewing/generate.sh [DIR]   (default cases/import/freesewing)"
  exit 0
fi
# Penelope (pencil skirt) without its back vent: the vent's flap is an
# overlap that the centre back seam of two mirrored pieces cannot sew.
node "$here/draft.mjs" penelope --model cisFemaleAdult36 --outdir "$out" --option backVent=false
# Aaron (tank top): front and back cut on the fold, shoulder and side seams.
node "$here/draft.mjs" aaron --model cisFemaleAdult36 --outdir "$out"
# Bella (bodice block): front with waist and side bust darts, cut on the
# fold; back with a waist dart, cut 2; sleeve.
node "$here/draft.mjs" bella --model cisFemaleAdult36 --outdir "$out"
