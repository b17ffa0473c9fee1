#!/usr/bin/env bash
# Runs `sartor creep` for one linear-elastic fabric direction and checks its
# creep.csv against the closed form (check_creep_csv.sh):
#
#   creep_closed_form.sh SARTOR OUTDIR "SIGMA K E ALPHA LL LU T TEND" [CREEP OPTIONS...]
#
# --no-plot and --output OUTDIR are added to the creep options.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 SARTOR OUTDIR \"SIGMA K E ALPHA LL LU T TEND\" [OPTIONS...]" >&2; exit 2; }
sartor=$1 out=$2 expected=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
"$sartor" creep "$@" --no-plot --output "$out"
[ ! -e "$out/creep.png" ] || { echo "creep_closed_form: --no-plot, but creep.png exists" >&2; exit 1; }
# shellcheck disable=SC2086 # the nine numbers are meant to split
bash "$here/check_creep_csv.sh" "$out/creep.csv" $expected
