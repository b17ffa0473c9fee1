#!/usr/bin/env bash
# The same job on 1, 2 and 4 ranks ends in the same state: compare_runs.py
# holds the 2- and 4-rank results to the 1-rank one within its tolerances
# (positions 1e-6 m, tensions 1e-6 of the largest; docs/reliability.md#mpi-
# determinism). Another partition sums in another order, so the runs differ
# by round-off, and nothing the solver decides may hinge on it.
#
#   ranks_agree.sh MPIEXEC OUTDIR SARTOR ARGS...
set -euo pipefail
[ $# -ge 4 ] || { echo "usage: $0 MPIEXEC OUTDIR SARTOR ARGS..." >&2; exit 2; }
mpiexec=$1 out=$2 sartor=$3
shift 3
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
flags=(--oversubscribe)
[ "$(id -u)" = 0 ] && flags+=(--allow-run-as-root)
rm -rf "$out"
mkdir -p "$out"
for ranks in 1 2 4; do
  "$mpiexec" "${flags[@]}" -n "$ranks" "$sartor" "$@" --no-plot --output "$out/ranks_$ranks" \
    > "$out/ranks_$ranks.log" 2>&1 ||
    { cat "$out/ranks_$ranks.log"; echo "ranks_agree.sh: the run on $ranks ranks failed"; exit 1; }
  tail -n 1 "$out/ranks_$ranks.log"
done
for ranks in 2 4; do
  echo "1 rank against $ranks:"
  /usr/bin/python3 "$here/compare_runs.py" "$out/ranks_1" "$out/ranks_$ranks"
done
