#!/usr/bin/env bash
# The same job twice on the same number of ranks must give the same bits
# (docs/reliability.md#mpi-determinism): every dataset of result.h5 and
# series.h5 equal, and the same path: the same steps, rejections, Newton
# iterations and energies.
#
#   mpi_rerun.sh MPIEXEC RANKS OUTDIR SARTOR ARGS...
set -euo pipefail
[ $# -ge 5 ] || { echo "usage: $0 MPIEXEC RANKS OUTDIR SARTOR ARGS..." >&2; exit 2; }
mpiexec=$1 ranks=$2 out=$3 sartor=$4
shift 4
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
flags=(--oversubscribe)
[ "$(id -u)" = 0 ] && flags+=(--allow-run-as-root)
rm -rf "$out"
mkdir -p "$out"
for run in first second; do
  "$mpiexec" "${flags[@]}" -n "$ranks" "$sartor" "$@" --no-plot --output "$out/$run" \
    > "$out/$run.log"
done
"$python" - "$out" <<'PY'
import json, os, sys
import h5py, numpy as np

out = sys.argv[1]

def datasets(path):
    found = {}
    with h5py.File(path) as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj[()])
                     if isinstance(obj, h5py.Dataset) else None)
    return found

compared = 0
for name in ("result.h5", "series.h5"):
    first = os.path.join(out, "first", name)
    if not os.path.exists(first):
        continue
    a, b = datasets(first), datasets(os.path.join(out, "second", name))
    assert a.keys() == b.keys(), f"{name}: different datasets"
    for key in a:
        assert np.array_equal(a[key], b[key]), f"{name}:{key} differs between the reruns"
        compared += 1
assert compared > 0, "no result.h5 or series.h5 written"

def path(run):
    # What the solver did, without wall-clock timings: the steps of a
    # dynamic run (time, step, Newton iterations, rejections, energies), or
    # the static solve's iteration count.
    with open(os.path.join(out, run, "summary.json")) as f:
        s = json.load(f)
    return {"history": s.get("dynamics", {}).get("history"),
            "newton_iterations": s.get("solver", {}).get("newton_iterations")}

assert path("first") == path("second"), "the reruns took different paths"
steps = len(path("first")["history"] or [])
print(f"mpi_rerun: {compared} datasets bit-identical, the same path ({steps} steps)")
PY
