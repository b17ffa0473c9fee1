#!/usr/bin/env bash
# Coarse-to-fine statics of `sartor run` (--refine-levels N): each level is
# the case's mesh with one refinement more, started from the level before
# (its new vertices at the solved edges' midpoints).
# 1. Hencky's membrane (a unique equilibrium, no contact): the 3-level solve
#    must land on the one-level solve's centre deflection (both solved to
#    the residual tolerance: within 1e-7 of it), report three levels whose
#    meshes are successive refinements (4x the triangles each), and take
#    fewer Newton iterations on the finest mesh than the one-level solve
#    took there (it starts from the interpolated coarse solution).
# 2. The static sphere drape on 8 x 8 cells refined once: every level
#    certified, the finer level's start lifted out of the ball.
# 3. The flat-start catenary (pins moved in with the load, 4 load steps) on
#    two levels: the finer level starts loaded, in one load step, and hangs
#    as the one-level solve does (sag within 1e-6 m).
# 4. `sartor converge --prolong` on Hencky (3 levels): the same values as
#    without it (within 1e-7), each finer level in fewer Newton iterations.
#   run_refine_levels.sh SARTOR HENCKY.yaml SPHERE.yaml CATENARY.yaml WORKDIR
set -euo pipefail
sartor=$1 hencky=$2 sphere=$3 catenary=$4 work=$5
rm -rf "$work" && mkdir -p "$work"
run() {
  local name=$1
  shift
  "$sartor" run "$@" --no-plot --output "$work/$name" > "$work/$name.log" 2>&1 ||
    { cat "$work/$name.log" >&2; echo "$name: exit status $?" >&2; exit 1; }
}
run hencky_one "$hencky" --mesh-rings 6 --mesh-refine 2
run hencky_levels "$hencky" --mesh-rings 6 --mesh-refine 2 --refine-levels 3
run sphere "$sphere" --mesh-nx 8 --mesh-ny 8 --mesh-refine 1 --refine-levels 2
run catenary_one "$catenary" --mesh-refine 1 --load-steps 4
run catenary_levels "$catenary" --mesh-refine 1 --load-steps 4 --refine-levels 2
for start in placement prolonged; do
  flag=()
  [ "$start" = prolonged ] && flag=(--prolong)
  "$sartor" converge "$hencky" --levels 3 --mesh-rings 4 --mesh-snap-boundary --probe 0,0,0 \
    "${flag[@]}" --no-plot --output "$work/converge_$start" > "$work/converge_$start.log" 2>&1 ||
    { cat "$work/converge_$start.log" >&2; exit 1; }
done
grep -q "level 3 of 3" "$work/hencky_levels.log" || { cat "$work/hencky_levels.log" >&2; exit 1; }
/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
failures = []
one = json.load(open(f"{work}/hencky_one/summary.json"))
levels = json.load(open(f"{work}/hencky_levels/summary.json"))
w_one = one["probe"]["displacement_m"][2]
w_levels = levels["probe"]["displacement_m"][2]
if not abs(w_levels - w_one) <= 1e-7 * abs(w_one):
    failures.append(f"Hencky: w0 {w_levels} on levels against {w_one} on one mesh")
runs = levels.get("levels", [])
if [r["mesh_refine"] for r in runs] != [0, 1, 2]:
    failures.append(f"Hencky: levels {[r.get('mesh_refine') for r in runs]}, expected 0, 1, 2")
for coarse, fine in zip(runs, runs[1:]):
    if fine["triangles"] != 4 * coarse["triangles"]:
        failures.append(f"Hencky: {fine['triangles']} triangles after {coarse['triangles']}")
if runs and runs[-1]["vertices"] != one["mesh"]["vertices"]:
    failures.append("Hencky: the finest level is not the case's mesh")
if not all(r["converged"] and r["certificate"] == "certified" for r in runs):
    failures.append(f"Hencky: a level not certified: {runs}")
finest, single = levels["solver"]["newton_iterations"], one["solver"]["newton_iterations"]
if not finest < single:
    failures.append(f"Hencky: {finest} Newton iterations on the finest level, {single} on one")
sphere = json.load(open(f"{work}/sphere/summary.json"))
runs = sphere.get("levels", [])
if len(runs) != 2 or not all(r["certificate"] == "certified" for r in runs):
    failures.append(f"sphere: levels {runs}")
if not sphere["certificate"]["certified"]:
    failures.append(f"sphere: {sphere['certificate']['verdict']}")
if len(runs) == 2 and not runs[1]["start_depth_below_offset_m"] >= 0.0:
    failures.append("sphere: the finer level's start depth is not reported")
one = json.load(open(f"{work}/catenary_one/summary.json"))
levels = json.load(open(f"{work}/catenary_levels/summary.json"))
sag_one, sag_levels = one["probe"]["displacement_m"][2], levels["probe"]["displacement_m"][2]
if not abs(sag_one - sag_levels) <= 1e-6:
    failures.append(f"catenary: sag {sag_levels} on levels, {sag_one} on one")
if len(levels["load_steps"]) != 1 or not levels["certificate"]["certified"]:
    failures.append(f"catenary: finest level in {len(levels['load_steps'])} load steps, "
                    f"{levels['certificate']['verdict']}")
placement = json.load(open(f"{work}/converge_placement/convergence.json"))
prolonged = json.load(open(f"{work}/converge_prolonged/convergence.json"))
if prolonged["start"] != "prolonged" or placement["start"] != "placement":
    failures.append(f"converge: start {placement['start']}, {prolonged['start']}")
for a, b in zip(placement["rows"], prolonged["rows"]):
    if not abs(a["value"] - b["value"]) <= 1e-7 * abs(a["value"]):
        failures.append(f"converge level {a['level']}: {b['value']} prolonged, {a['value']}")
    if a["level"] > 0 and not b["newton_iterations"] < a["newton_iterations"]:
        failures.append(f"converge level {a['level']}: {b['newton_iterations']} Newton "
                        f"prolonged, {a['newton_iterations']} from the placement")
print(f"Hencky w0 {w_levels:.9e} (one level {w_one:.9e}); Newton on the finest mesh "
      f"{finest} (one level {single}); sphere levels "
      f"{[r['newton_iterations'] for r in runs]}")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
