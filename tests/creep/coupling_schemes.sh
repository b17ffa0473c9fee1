#!/usr/bin/env bash
# The two coupling schemes and the dynamic variant of `sartor run --analysis
# creep` end to end (docs/creep-structure.md):
#  * monolithic on the creep strip follows `sartor creep` (the material law)
#    at every output time to 1e-6 relative, on 1 and on 2 ranks (1e-9 apart);
#  * its tangent passes -snes_test_jacobian (||J - Jfd|| / ||J|| < 1e-5) on the
#    pinch, a sheet in tension both ways (away from the law's kink at zero
#    tension), with the held pinch's rows;
#  * the relaxation's time-step convergence: observed order 1 for staggered,
#    2 for monolithic (postproc/creep_convergence.py);
#  * the dynamic variant (--creep-dynamics) follows the law too, and a run
#    resumed from its mid-way checkpoint (with velocities) ends bit-identical
#    to the uninterrupted one; a quasi-static restart of it is refused;
#  * pins let go in time (--pin-release) on 1 and 2 ranks, and its bad uses.
#   coupling_schemes.sh SARTOR CASES_DIR STUDY_SCRIPT WORKDIR MPIEXEC [FLAGS...]
set -euo pipefail
sartor=$1 cases=$2 study=$3 work=$4 mpiexec=$5
shift 5
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
strip=$cases/strip.yaml relaxation=$cases/relaxation.yaml

"$sartor" creep --fabric cotton_twill:warp --sample-interval 60 --no-plot \
  --output "$work/law" > "$work/law.log"
"$sartor" run "$strip" --creep-scheme monolithic --output "$work/monolithic" > "$work/monolithic.log"
"$mpiexec" -n 2 "$@" "$sartor" run "$strip" --creep-scheme monolithic \
  --output "$work/monolithic_2" > "$work/monolithic_2.log"
dynamic=(--creep-dynamics --density 0.3 --damping 5)
"$sartor" run "$strip" "${dynamic[@]}" --output "$work/dynamic" > "$work/dynamic.log"
# Resumed at 30 s, while the strip still creeps (moves): 10 min in all.
dynamic+=(--checkpoint-interval 10 --output-interval 60)
"$sartor" run "$strip" "${dynamic[@]}" --time-end 600 --output "$work/whole" > "$work/whole.log"
"$sartor" run "$strip" "${dynamic[@]}" --time-end 30 --output "$work/first_half" \
  > "$work/first_half.log"
"$sartor" run "$strip" "${dynamic[@]}" --time-end 600 --restart "$work/first_half/checkpoint.h5" \
  --output "$work/second_half" > "$work/second_half.log"
if "$sartor" run "$strip" --restart "$work/first_half/checkpoint.h5" --output "$work/refused" \
  > "$work/refused.log" 2>&1; then
  echo "a quasi-static restart from a dynamic checkpoint was accepted" >&2
  exit 1
fi
grep -q "the checkpoint is of a dynamic (--creep-dynamics) run" "$work/refused.log" ||
  { cat "$work/refused.log" >&2; exit 1; }

# Pins let go (--pin-release): the pinch case on 1 and 2 ranks; bad uses refused.
"$sartor" run "$cases/pinch.yaml" --output "$work/pinch_1" > "$work/pinch_1.log"
"$mpiexec" -n 2 "$@" "$sartor" run "$cases/pinch.yaml" --output "$work/pinch_2" > "$work/pinch_2.log"
refused() { # EXPECTED-MESSAGE ARGS...
  local message=$1
  shift
  if "$sartor" run "$cases/pinch.yaml" --output "$work/refused_release" "$@" \
    > "$work/refused_release.log" 2>&1; then
    echo "accepted: $*" >&2
    exit 1
  fi
  grep -qF "$message" "$work/refused_release.log" || { cat "$work/refused_release.log" >&2; exit 1; }
}
refused "pins let go in time; give --analysis dynamic or creep" --analysis static
refused "'1-3' is not BOX:TIME" --pin-release 1-3
refused "box 2 is not a box of --pin-box (1..1)" --pin-release 2:3

"$sartor" run "$cases/pinch.yaml" --creep-scheme monolithic --time-end 1 --mesh-nx 6 --mesh-ny 6 \
  --pin-box -0.03,0.03,-0.03,0.03,-0.001,0.001 --output "$work/jacobian" -snes_test_jacobian \
  > "$work/jacobian.log"
"$study" --sartor "$sartor" --case "$relaxation" --steps 0.5,0.25,0.125 --reference-step 0.015625 \
  --no-plot "$work/study" > "$work/study.log"

"$python" - "$work" "$(dirname "$0")/../cli" <<'PY'
import csv, json, re, sys
import h5py, numpy as np
work = sys.argv[1]
sys.path.insert(0, sys.argv[2])
import strip_law
failures = []

law = strip_law.law_strains(f"{work}/law/creep.csv")
def against_law(run):
    compared, worst = strip_law.compare(law, f"{work}/{run}/creep.csv")
    if compared < 121 or worst > 1e-6:
        failures.append(f"{run} vs the creep law: {compared} times, worst relative {worst:.3g}")
    print(f"{run}: {compared} output times against `sartor creep`, worst relative {worst:.2e}")
for run in ("monolithic", "dynamic"):
    against_law(run)

one = list(csv.DictReader(open(f"{work}/monolithic/creep.csv")))
two = list(csv.DictReader(open(f"{work}/monolithic_2/creep.csv")))
if len(one) != len(two) or any(
        abs(float(a["probe_dx_m"]) - float(b["probe_dx_m"])) > 1e-9 * abs(float(a["probe_dx_m"]))
        for a, b in zip(one, two)):
    failures.append("monolithic: 2 ranks differ from 1 rank")

ratios = [float(m) for m in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)",
                                       open(f"{work}/jacobian.log").read())]
if len(ratios) < 3 or max(ratios) > 1e-5:
    failures.append(f"-snes_test_jacobian: {len(ratios)} checks, largest ratio {max(ratios, default=0):.3g}")
print(f"monolithic tangent: {len(ratios)} -snes_test_jacobian checks, largest ratio {max(ratios):.2e}")

study = json.load(open(f"{work}/study/convergence.json"))
for scheme, (low, high) in {"staggered": (0.7, 1.3), "monolithic": (1.8, 2.2)}.items():
    for quantity in ("tension_end_of_hold_N_per_m", "permanent_strain_at_end"):
        order = study["orders"][scheme][quantity][-1]
        if not low <= order <= high:
            failures.append(f"{scheme} {quantity}: observed order {order:.2f}, expected {low}..{high}")
        print(f"{scheme:10s} {quantity}: observed order {order:.2f}")

with h5py.File(f"{work}/whole/result.h5") as a, h5py.File(f"{work}/second_half/result.h5") as b:
    for field in ("fields/position", "cell_fields/tension_warp", "cell_fields/strain_warp"):
        x, y = a[field][()], b[field][()]
        if np.abs(x - y).max() > 1e-12 * np.abs(x).max():
            failures.append(f"dynamic, resumed: {field} differs")
with h5py.File(f"{work}/first_half/checkpoint.h5") as h5:
    if "velocities" not in h5 or not np.abs(h5["velocities"][()]).max() > 0:
        failures.append("the dynamic checkpoint holds no velocities")
if open(f"{work}/whole/creep.csv").read() != open(f"{work}/second_half/creep.csv").read():
    failures.append("dynamic, resumed: creep.csv differs from the uninterrupted run's")
print("dynamic: resumed at 30 s from a checkpoint with velocities, final state identical")
def lowest(run):
    return min(float(l.split()[3]) for l in open(f"{work}/{run}/final.obj") if l.startswith("v "))
one_rank, two_ranks = lowest("pinch_1"), lowest("pinch_2")
# Agreement to the Newton tolerance: the ranks' solves stop at different
# iterates (measured 5e-9 apart).
if not (one_rank < -1e-3 and abs(one_rank - two_ranks) <= 1e-7 * abs(one_rank)):
    failures.append(f"released pinch: lowest point {one_rank:.6g} m (1 rank), {two_ranks:.6g} m (2 ranks)")
print(f"released pinch hangs to {one_rank:.4g} m on 1 and 2 ranks")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
