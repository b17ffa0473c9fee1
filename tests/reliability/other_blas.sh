#!/usr/bin/env bash
# Runs one sartor job twice, with the BLAS kernels this machine runs and
# with another CPU's (tests/support/other_blas_core.sh: Haswell's or
# Prescott's, whichever is not native; their round-off differs by ~1e-12
# relative on every dense BLAS result), and checks with compare_runs.py that the two agree within
# the stated tolerances (docs/reliability.md): nothing the solvers decide
# (accepted and rejected steps, Newton's path, step sizes) may hinge on
# round-off.
# usage: other_blas.sh OUTDIR SARTOR ARGS...   (the job writes to OUTDIR/{native,other})
set -euo pipefail
out="$1"
sartor="$2"
shift 2
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
. "$here/../support/other_blas_core.sh"
rm -rf "$out"
mkdir -p "$out"
# "Native" is the kernels this machine's OpenBLAS runs as the environment
# sets it up: where OPENBLAS_CORETYPE is set, it is kept, since OpenBLAS
# 0.3.21 misdetects some processors (an AMD EPYC as Cooperlake) and their
# kernels then round differently from any real machine's, or fail.
other=$(other_blas_core "$sartor")
"$sartor" "$@" --no-plot --output "$out/native" > "$out/native.log" 2>&1 ||
  { cat "$out/native.log"; echo "other_blas.sh: the native run failed"; exit 1; }
OPENBLAS_CORETYPE=$other "$sartor" "$@" --no-plot --output "$out/other" > "$out/other.log" 2>&1 ||
  { cat "$out/other.log"; echo "other_blas.sh: the run with $other's kernels failed"; exit 1; }
tail -n 1 "$out/native.log" "$out/other.log"
/usr/bin/python3 "$here/compare_runs.py" "$out/native" "$out/other"
