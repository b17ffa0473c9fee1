#!/bin/bash
# sartor edit's retry (docs/sensitivity.md#sartor-edit): with every re-solve
# cut off after one Newton iteration (--edit-max-newton 1), the hem edit of
# the coarse skirt fails from the linear prediction it was asked to start
# from, is tried again from the unchanged drape (the only other start while
# one design is solved: GMLS is then the linear prediction), fails again,
# and sartor edit exits with status 1 naming the edit, keeps the first
# attempt's state and lists both attempts in summary.json. With
# --no-edit-retry only the first is tried. Usage: edit_retry.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out" "$out"_once
args=("$root/cases/patterns/skirt.json" "$root/cases/edit/skirt_hem.yaml"
  -options_file_yaml "$root/cases/garments/skirt_coarse.yaml" --no-plot --no-edit-outputs
  --edit-start linear --edit-max-newton 1)
status=0
"$sartor" edit "${args[@]}" --output "$out" > "$out.log" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$out.log"; echo "exit status $status, not 1"; exit 1; }
grep -q "re-solve from linear (from unchanged: not converged): NOT converged" "$out.log" ||
  { cat "$out.log"; echo "no retry in the closing line"; exit 1; }
grep -q "the re-solve of edit_01 did not converge from any start tried" "$out.log" ||
  { cat "$out.log"; echo "no error naming the edit"; exit 1; }
status=0
"$sartor" edit "${args[@]}" --no-edit-retry --output "$out"_once > "$out"_once.log 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$out"_once.log; echo "--no-edit-retry: exit status $status, not 1"; exit 1; }
/usr/bin/python3 - "$out/summary.json" "$out"_once/summary.json <<'PY'
import json, sys
retried, once = (json.load(open(path))["edit"]["steps"] for path in sys.argv[1:])
assert len(retried) == 1 and len(once) == 1, (len(retried), len(once))
step = retried[0]
attempts = step["attempts"]
assert [a["start"] for a in attempts] == ["linear", "unchanged"], attempts
assert not any(a["converged"] or a["certified"] for a in attempts), attempts
# Every solve of an attempt stops at its first Newton iteration.
assert all(0 < a["newton_iterations"] for a in attempts), attempts
assert step["start"] == "linear" and not step["resolve"]["converged"], step["resolve"]
assert set(step["start_energy_J"]) == {"linear", "unchanged"}, step["start_energy_J"]
assert abs(step["cpu_s"]["resolve"] - sum(a["cpu_s"] for a in attempts)) < 1e-9, step["cpu_s"]
assert [a["start"] for a in once[0]["attempts"]] == ["linear"], once[0]["attempts"]
print("attempts:", [(a["start"], a["reason"], a["newton_iterations"]) for a in attempts])
PY
