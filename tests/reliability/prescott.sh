#!/usr/bin/env bash
# Runs one sartor job twice, with OpenBLAS's kernels for this CPU and with
# OPENBLAS_CORETYPE=Prescott (another CPU's rounding, ~1e-12 relative on every
# dense BLAS result), and checks with compare_runs.py that the two agree
# within the stated tolerances (docs/reliability.md): nothing the solvers
# decide (accepted and rejected steps, Newton's path, step sizes) may hinge
# on round-off.
# usage: prescott.sh OUTDIR SARTOR ARGS...   (the job writes to OUTDIR/{native,prescott})
set -euo pipefail
out="$1"
sartor="$2"
shift 2
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$out"
mkdir -p "$out"
# "Native" is the kernels this machine's OpenBLAS runs as the environment
# sets it up: where OPENBLAS_CORETYPE is set, it is kept, since OpenBLAS
# 0.3.21 misdetects some processors (an AMD EPYC as Cooperlake) and their
# kernels then round differently from any real machine's, or fail.
"$sartor" "$@" --no-plot --output "$out/native" > "$out/native.log" 2>&1 ||
  { cat "$out/native.log"; echo "prescott.sh: the native run failed"; exit 1; }
OPENBLAS_CORETYPE=Prescott "$sartor" "$@" --no-plot --output "$out/prescott" > "$out/prescott.log" 2>&1 ||
  { cat "$out/prescott.log"; echo "prescott.sh: the Prescott run failed"; exit 1; }
tail -n 1 "$out/native.log" "$out/prescott.log"
/usr/bin/python3 "$here/compare_runs.py" "$out/native" "$out/prescott"
