#!/usr/bin/env bash
# The same static drape on "another machine": `sartor drape` by its default,
# the static minimiser, once as it is and once with OpenBLAS forced to
# another CPU's kernels (tests/support/other_blas_core.sh: Haswell's or
# Prescott's, whichever this machine does not run), which changes the
# round-off of every BLAS operation (~1e-12) as a different processor would.
# The solver takes no decision on round-off (docs/drape.md#the-static-
# minimiser), so both runs converge to the same equilibrium: every vertex of
# final.obj within 1e-6 m (issue 18: drapes agree within 1e-6 m on another
# machine; the garments agree to about 1e-8 m, the solver's tolerance).
#
#   drape_other_blas_agrees.sh SARTOR PATTERN CASE OUT_DIR [DRAPE_OPTION ...]
set -euo pipefail
[ $# -ge 4 ] || { echo "usage: $0 SARTOR PATTERN CASE OUT_DIR [DRAPE_OPTION ...]" >&2; exit 2; }
sartor=$1 pattern=$2 case=$3 dir=$4
shift 4
python=/usr/bin/python3
. "$(dirname "${BASH_SOURCE[0]}")/../support/other_blas_core.sh"
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
mkdir -p "$dir"
"$sartor" drape "$pattern" -options_file_yaml "$case" --no-plot "$@" --output "$dir/default" \
  > "$dir/default.log"
OPENBLAS_CORETYPE=$(other_blas_core "$sartor") "$sartor" drape "$pattern" -options_file_yaml "$case" \
  --no-plot "$@" --output "$dir/other" > "$dir/other.log"
"$python" - "$dir" 1e-6 <<'PY'
import json, os, sys
d, tolerance = sys.argv[1], float(sys.argv[2])

def vertices(run):
    with open(os.path.join(d, run, "final.obj")) as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]

def summary(run):
    with open(os.path.join(d, run, "summary.json")) as f:
        return json.load(f)

a, b = vertices("default"), vertices("other")
assert len(a) == len(b) and a, (len(a), len(b))
for run in ("default", "other"):
    s = summary(run)
    assert s["converged"] and s["drape"]["method"] == "minimise", (run, s["solver"])
apart = max(max(abs(p - q) for p, q in zip(u, v)) for u, v in zip(a, b))
iterations = [summary(run)["solver"]["newton_iterations"] for run in ("default", "other")]
print("drape_other_blas_agrees: %d vertices, %s Newton iterations, the runs %.2e m apart"
      % (len(a), iterations, apart))
assert apart < tolerance, f"the default and other kernels' drapes end {apart} m apart (bound {tolerance} m)"
PY
