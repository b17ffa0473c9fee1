#!/usr/bin/env bash
# kill -9 at pseudo-random moments and resume (docs/reliability.md#checkpoints-and-restart),
# one SCENARIO at a time (each its own ctest test, so that only the wear's
# holds two cores):
#   plate_sheet    a static run in 40 load steps (the slit annular plate)
#                  and a dynamic run (the swinging sheet);
#   skirt          a static drape (the skirt: sewing stages and contact
#                  rounds), the same on two refinement levels (killed at
#                  random moments, and once within the second level), and
#                  checkpoints resumed by the wrong kind of run refused;
#   skirt_dynamic  a dynamic drape (the skirt sewn in time), on one level
#                  and killed within the second of two;
#   wear           a static drape worn for 40 s on 2 ranks (killed once
#                  within the wear after its first take-off).
# Each is run once uninterrupted, then again with checkpoints, killed with
# SIGKILL a few times, shortly after checkpoints drawn from a fixed seed (the
# first after its first checkpoint), resumed with --restart into the same output
# folder each time, and finally let finish. The final positions, and the
# states of series.h5 and dynamics.csv, must equal the uninterrupted run's
# within 1e-6 m (the drapes' solver tolerance is 1e-6 of the weight in
# force; the displacements are 0.05 to 1 m), and the static run's load steps
# (load factors, Newton iterations), the static drapes' contact rounds and
# the wear's tables must be the uninterrupted run's. The differences are printed.
#   kill_resume.sh SARTOR PROJECT_DIR WORKDIR MPIEXEC SCENARIO
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: $0 SARTOR PROJECT_DIR WORKDIR MPIEXEC SCENARIO" >&2; exit 2; }
sartor=$1 project=$2 work=$3 scenario=$5
on_two_ranks=("$4" --oversubscribe -n 2)
[ "$(id -u)" = 0 ] && on_two_ranks+=(--allow-run-as-root)
python=/usr/bin/python3
"$python" -c "import h5py, numpy" 2> /dev/null || { echo "error: $python lacks h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
RANDOM=18 # the seed of the kill moments

# await_checkpoint OUT PID changes COUNT: waits until OUT/checkpoint.h5 has
# held COUNT states other than the one it held at the start (none, or the
# one resumed). await_checkpoint OUT PID state CONDITION: until its /state
# makes CONDITION (a Python expression of `state`, the parsed JSON) true.
# Fails when the run ends first. The kills wait on the run's progress, not
# on the clock: a faster machine ends the runs sooner, never before their
# kills.
await_checkpoint() {
  "$python" - "$1/checkpoint.h5" "$2" "$3" "$4" <<'PY'
import json, os, sys, time
import h5py
path, pid, kind, argument = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]

def text():
    try:
        with h5py.File(path, "r") as f:
            return f["state"][()].tobytes()
    except (OSError, KeyError):
        return None  # not written yet, or being replaced

def reached(current, seen):
    if kind == "changes":
        if current != seen[-1]:
            seen.append(current)
        return len(seen) > int(argument)
    try:
        return bool(eval(argument, {}, {"state": json.loads(current.decode())}))
    except (KeyError, ValueError):
        return False  # not a whole state yet, or not one the condition reads

seen = [text()]
deadline = time.monotonic() + 300  # 5 min on a loaded machine
while time.monotonic() < deadline:
    current = text()
    if current is not None and reached(current, seen):
        sys.exit(0)
    try:
        os.kill(pid, 0)
    except OSError:
        sys.exit(1)  # the run ended first
    time.sleep(0.02)
sys.exit(1)
PY
}

# interrupted NAME KILLS ARGS...: runs ARGS into $work/NAME with checkpoints,
# killing it KILLS times; every start after a kill resumes the last checkpoint.
# Each kill comes 0 to 90 ms after the run's first to third new checkpoint
# (the first kill after its first), drawn from the seed: within a step, or
# while a checkpoint is being written.
interrupted() {
  local name=$1 kills=$2
  shift 2
  local out="$work/$name" log="$work/$name.log" restart=() kill_count=0
  for attempt in $(seq 0 "$kills"); do
    "$sartor" "$@" "${restart[@]}" --output "$out" >> "$log" 2>&1 &
    local pid=$!
    if [ "$attempt" -lt "$kills" ]; then
      local checkpoints=$((attempt == 0 ? 1 : 1 + RANDOM % 3)) delay
      delay=0.0$((RANDOM % 10))
      if await_checkpoint "$out" "$pid" changes "$checkpoints"; then
        sleep "$delay"
        if kill -9 "$pid" 2> /dev/null; then
          kill_count=$((kill_count + 1))
          echo "$name: killed $delay s after its ${checkpoints}. new checkpoint (kill $kill_count)" |
            tee -a "$log"
        fi
      fi
      wait "$pid" 2> /dev/null || true
      [ -s "$out/checkpoint.h5" ] || { cat "$log" >&2; echo "$name: no checkpoint before the kill" >&2; exit 1; }
      restart=(--restart "$out/checkpoint.h5")
      [ -e "$out/summary.json" ] && break # it finished before the kill
    else
      wait "$pid" || { cat "$log" >&2; echo "$name: the resumed run failed" >&2; exit 1; }
    fi
  done
  [ "$kill_count" -gt 0 ] || { cat "$log" >&2; echo "$name: every run ended before its kill" >&2; exit 1; }
  grep -q "resuming from" "$log" || { echo "$name: never resumed" >&2; exit 1; }
}

# The plate: 40 load steps, a checkpoint after each. The sheet: the patch
# model on 12 x 12 cells, a checkpoint every 0.05 s of its 1.5 s swing.
plate=("$project/cases/fe/slit_annular_plate.yaml" --no-plot)
sheet=("$project/cases/fe/hanging_sheet_dynamic.yaml" --mesh-nx 12 --mesh-ny 12 --time-end 1.5
  --bending-model patch --output-interval 0.1 --no-plot)
skirt=("$project/cases/patterns/skirt.json" --edge-length 0.08 --no-plot)
skirt_levels=("${skirt[@]}" --levels 2)
skirt_dynamic=("${skirt[@]}" --analysis dynamic --time-end 0.2 --sewing-time 0.1 -settle false)
skirt_dynamic_levels=("${skirt_levels[@]}" --analysis dynamic --time-end 0.2 --sewing-time 0.1 -settle false)

# Within the finer level of a drape on two levels: killed once the first
# checkpoint within level 2 is written (/state's drape_level), resumed from
# there (static: after a sewing stage; dynamic: at a multiple of 0.02 s).
# killed_in_level2 NAME ARGS...: drape ARGS into $work/NAME, killed within level 2, resumed.
killed_in_level2() {
  local name=$1 out="$work/$1"
  shift
  "$sartor" drape "$@" --output "$out" > "$out.log" 2>&1 &
  local pid=$!
  await_checkpoint "$out" "$pid" state 'state.get("drape_level", {}).get("level") == 1' ||
    { cat "$out.log" >&2; echo "$name: no checkpoint within level 2" >&2; exit 1; }
  kill -9 "$pid" && wait "$pid" 2> /dev/null || true
  "$sartor" drape "$@" --restart "$out/checkpoint.h5" --output "$out" >> "$out.log" 2>&1 ||
    { cat "$out.log" >&2; echo "$name: the resumed run failed" >&2; exit 1; }
  grep -q "resuming from .* within level 2 of 2" "$out.log" ||
    { cat "$out.log" >&2; echo "$name: did not resume within level 2" >&2; exit 1; }
}

# refused NAME MESSAGE ARGS...: sartor ARGS must fail, its log holding MESSAGE.
refused() {
  local name=$1 message=$2
  shift 2
  if "$sartor" "$@" --output "$work/$name" > "$work/$name.log" 2>&1; then
    echo "$name: sartor $* was not refused" >&2
    exit 1
  fi
  grep -q -- "$message" "$work/$name.log" || { cat "$work/$name.log" >&2; exit 1; }
}

# The plate in load steps and the sheet's swing.
run_plate_sheet() {
  "$sartor" run "${plate[@]}" --output "$work/plate_whole" > "$work/plate_whole.log"
  interrupted plate 3 run "${plate[@]}" --checkpoint-interval 1
  "$sartor" run "${sheet[@]}" --output "$work/sheet_whole" > "$work/sheet_whole.log"
  interrupted sheet 3 run "${sheet[@]}" --checkpoint-interval 0.05
}

# The static drape on one and on two levels, and killed within level 2.
run_skirt() {
  "$sartor" drape "${skirt[@]}" --output "$work/skirt_whole" > "$work/skirt_whole.log"
  interrupted skirt 3 drape "${skirt[@]}" --checkpoint-interval 1
  "$sartor" drape "${skirt_levels[@]}" --output "$work/skirt_levels_whole" > "$work/skirt_levels_whole.log"
  interrupted skirt_levels 2 drape "${skirt_levels[@]}" --checkpoint-interval 1
  killed_in_level2 skirt_level2 "${skirt_levels[@]}" --checkpoint-interval 1
  # A checkpoint within a level resumes only a drape with the same levels;
  # one of another kind of run is refused, with its file named.
  refused wrong_levels "within a level of a drape on several levels; resume it with the same --levels" \
    drape "${skirt[@]}" --levels 1 --restart "$work/skirt_level2/checkpoint.h5"
  refused wrong "skirt/checkpoint.h5: the checkpoint is not of an --analysis dynamic run" \
    run "${sheet[@]}" --restart "$work/skirt/checkpoint.h5"
}

# The dynamic drape on one level, and killed within level 2 of two.
run_skirt_dynamic() {
  "$sartor" drape "${skirt_dynamic_levels[@]}" --output "$work/skirt_dynamic_levels_whole" \
    > "$work/skirt_dynamic_levels_whole.log"
  killed_in_level2 skirt_dynamic_level2 "${skirt_dynamic_levels[@]}" --checkpoint-interval 0.02
  "$sartor" drape "${skirt_dynamic[@]}" --output "$work/skirt_dynamic_whole" \
    > "$work/skirt_dynamic_whole.log"
  interrupted skirt_dynamic 2 drape "${skirt_dynamic[@]}" --checkpoint-interval 0.02
}

# Within the wear after the drape, on 2 ranks: killed (every rank) once a
# checkpoint within the wear holds its first take-off (/state: kind "wear",
# one take-off), resumed from there on 2 ranks: the drape from the
# checkpoint's /before, the wear from its state. 40 s of wear in 15 steps,
# taken off at 8 s and at 40 s (about 35 s of wall time).
run_wear() {
  local skirt_wear=("${skirt[@]}" --wear-time 40 --take-off-times 8,40 --recovery-time 30
    --wear-first-step 2 --creep-tolerance 1e-2 -snes_max_it 2000)
  "${on_two_ranks[@]}" "$sartor" drape "${skirt_wear[@]}" --output "$work/skirt_wear_whole" \
    > "$work/skirt_wear_whole.log"
  local out="$work/skirt_wear"
  "${on_two_ranks[@]}" "$sartor" drape "${skirt_wear[@]}" --checkpoint-interval 1 --output "$out" \
    > "$out.log" 2>&1 &
  local pid=$!
  await_checkpoint "$out" "$pid" state 'state.get("kind") == "wear" and len(state["take_offs"]) >= 1' ||
    { cat "$out.log" >&2; echo "skirt_wear: no checkpoint within the wear" >&2; exit 1; }
  pkill -9 -f -- "--output $out\$" || true # the ranks, as a node failure would
  kill -9 "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  # wear.csv grows row by row: the killed run leaves its states up to the take-off at 8 s.
  awk -F, 'NR > 1 && $1 > 7.99 { found = 1 } END { exit !found }' "$out/wear.csv" ||
    { cat "$out.log" >&2; echo "skirt_wear: the killed run left no wear.csv row at 8 s" >&2; exit 1; }
  "${on_two_ranks[@]}" "$sartor" drape "${skirt_wear[@]}" --checkpoint-interval 1 \
    --restart "$out/checkpoint.h5" --output "$out" >> "$out.log" 2>&1 ||
    { cat "$out.log" >&2; echo "skirt_wear: the resumed run failed" >&2; exit 1; }
  grep -q "resuming the wear from .* at t = " "$out.log" ||
    { cat "$out.log" >&2; echo "skirt_wear: did not resume within the wear" >&2; exit 1; }
  # A checkpoint within the wear resumes only a drape with the wear.
  refused wrong_wear "was taken within a wear; resume it with the same --wear-time" \
    drape "${skirt[@]}" --restart "$out/checkpoint.h5"
}

case "$scenario" in
  plate_sheet) run_plate_sheet ;;
  skirt) run_skirt ;;
  skirt_dynamic) run_skirt_dynamic ;;
  wear) run_wear ;;
  *) echo "$0: unknown scenario '$scenario' (plate_sheet, skirt, skirt_dynamic or wear)" >&2; exit 2 ;;
esac

"$python" - "$work" "$scenario" <<'PY'
import csv, json, sys
import h5py, numpy as np
work, scenario = sys.argv[1:3]
tolerance = 1e-6  # m
failures = []
# The resumed runs of the scenario and the uninterrupted runs they must equal.
resumed = {"plate_sheet": (("plate", "plate"), ("sheet", "sheet")),
           "skirt": (("skirt", "skirt"), ("skirt_levels", "skirt_levels"),
                     ("skirt_level2", "skirt_levels")),
           "skirt_dynamic": (("skirt_dynamic_level2", "skirt_dynamic_levels"),
                             ("skirt_dynamic", "skirt_dynamic")),
           "wear": ()}[scenario]

def largest_difference(name, whole):
    with h5py.File(f"{work}/{whole}_whole/result.h5") as a, h5py.File(f"{work}/{name}/result.h5") as b:
        x, y = a["fields/position"][()], b["fields/position"][()]
        moved = np.abs(x - a["mesh/initial_position"][()]).max() if "mesh/initial_position" in a else None
        return np.abs(x - y).max(), moved

for name, whole in resumed:
    diff, moved = largest_difference(name, whole)
    print(f"{name}: resumed final positions differ by {diff:.3g} m from the uninterrupted run's"
          + (f" (largest displacement {moved:.3g} m)" if moved is not None else ""))
    if not diff <= tolerance:
        failures.append(f"{name}: final positions differ by {diff:.3g} m")

# The static drapes' contact rounds: a resume after the last round must not
# solve more of them (it did until 2026-12-07: the restored solves had no
# tolerance, so the friction was never found consistent and every round of
# --contact-rounds ran again).
drapes = {"skirt": resumed, "wear": (("skirt_wear", "skirt_wear"),)}.get(scenario, ())
for name, whole in drapes:
    rounds = [json.load(open(f"{work}/{n}/summary.json"))["solver"]["minimiser"]["contact_rounds"]
              for n in (f"{whole}_whole", name)]
    print(f"{name}: {rounds[1]} contact rounds, uninterrupted {rounds[0]}")
    if rounds[0] != rounds[1]:
        failures.append(f"{name}: {rounds[1]} contact rounds, uninterrupted {rounds[0]}")

if scenario == "plate_sheet":
    steps = [[(s["load_factor"], s["newton_iterations"])
              for s in json.load(open(f"{work}/{n}/summary.json"))["load_steps"]]
             for n in ("plate_whole", "plate")]
    print(f"plate: {len(steps[1])} load steps resumed, {len(steps[0])} uninterrupted")
    if steps[0] != steps[1]:
        failures.append(f"plate: load steps {steps[1]} differ from the uninterrupted run's {steps[0]}")

for name in {"plate_sheet": ("sheet",), "skirt_dynamic": ("skirt_dynamic",)}.get(scenario, ()):
    with h5py.File(f"{work}/{name}_whole/series.h5") as a, h5py.File(f"{work}/{name}/series.h5") as b:
        steps = sorted(a["steps"])
        if sorted(b["steps"]) != steps:
            failures.append(f"{name}: series.h5 has states {sorted(b['steps'])}, uninterrupted {steps}")
            continue
        worst = max(np.abs(a[f"steps/{s}/fields/position"][()] - b[f"steps/{s}/fields/position"][()]).max()
                    for s in steps)
        times = [a[f"steps/{s}/time"][0] == b[f"steps/{s}/time"][0] for s in steps]
        print(f"{name}: series.h5 {len(steps)} states, positions differ by at most {worst:.3g} m")
        if not (worst <= tolerance and all(times)):
            failures.append(f"{name}: series.h5 states differ by {worst:.3g} m or in time")
    rows = [list(csv.reader(open(f"{work}/{n}/dynamics.csv"))) for n in (f"{name}_whole", name)]
    if len(rows[0]) != len(rows[1]) or any(
            abs(float(p) - float(q)) > 1e-9 * max(1.0, abs(float(p)))
            for r, s in zip(rows[0][1:], rows[1][1:]) for p, q in zip(r[:6], s[:6])):
        failures.append(f"{name}: dynamics.csv differs from the uninterrupted run's")

# The wear: every row of wear.csv and takeoff.csv, and every state of
# wear/series.h5 and takeoff/series.h5.
for table in ("wear.csv", "takeoff.csv") if scenario == "wear" else ():
    rows = [list(csv.reader(open(f"{work}/{n}/{table}"))) for n in ("skirt_wear_whole", "skirt_wear")]
    def difference(p, q):  # numbers, or the certificate's verdict
        try:
            return abs(float(p) - float(q)) / max(1.0, abs(float(p)))
        except ValueError:
            return 0.0 if p == q else float("inf")
    worst = max((difference(p, q) for r, s in zip(rows[0][1:], rows[1][1:]) for p, q in zip(r, s)),
                default=0.0)
    print(f"skirt_wear: {table} {len(rows[1]) - 1} rows (uninterrupted {len(rows[0]) - 1}), "
          f"values differ by at most {worst:.3g} (relative, of those above 1)")
    if len(rows[0]) != len(rows[1]) or not worst <= 1e-9:
        failures.append(f"skirt_wear: {table} differs from the uninterrupted run's")
for series in ("wear", "takeoff") if scenario == "wear" else ():
    with h5py.File(f"{work}/skirt_wear_whole/{series}/series.h5") as a, \
         h5py.File(f"{work}/skirt_wear/{series}/series.h5") as b:
        steps = sorted(a["steps"])
        if sorted(b["steps"]) != steps:
            failures.append(f"skirt_wear: {series}/series.h5 has states {sorted(b['steps'])}, "
                            f"uninterrupted {steps}")
            continue
        worst = max(np.abs(a[f"steps/{s}/fields/position"][()] - b[f"steps/{s}/fields/position"][()]).max()
                    for s in steps)
        print(f"skirt_wear: {series}/series.h5 {len(steps)} states, positions differ by at most {worst:.3g} m")
        if not worst <= tolerance:
            failures.append(f"skirt_wear: {series}/series.h5 states differ by {worst:.3g} m")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
PY
