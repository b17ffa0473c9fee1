#!/bin/bash
# sartor edit DRAPE_DIR (docs/sensitivity.md#sartor-edit): the coarse skirt
# draped by `sartor drape`, then its hem edit from that directory, must give
# the edit that `sartor edit PATTERN` gives draping in the same run (the
# drape resumed from drape_state.h5 at full precision, with the drape's
# options), time its speed-up against the drape's recorded CPU time, leave
# the drape's directory as it was, and refuse what would edit another
# garment: a drape option changed, the drape's own directory as output, a
# pattern changed since, a directory without a drape state. Also: the
# re-solve starts from the geometric route when --edit-start asks for it.
# Usage: edit_drape_directory.sh SARTOR ROOT OUT
set -euo pipefail
sartor=$1 root=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
case=("-options_file_yaml" "$root/cases/garments/skirt_coarse.yaml" --no-plot)
edits=$root/cases/edit/skirt_hem.yaml
"$sartor" drape "$root/cases/patterns/skirt.json" "${case[@]}" --bending-model discrete_shell \
  --output "$out/drape" > "$out/drape.log" 2>&1 || { cat "$out/drape.log"; exit 1; }
test -s "$out/drape/drape_state.h5" || { echo "the drape wrote no drape_state.h5"; exit 1; }
before=$(md5sum "$out/drape/result.h5" "$out/drape/summary.json")
"$sartor" edit "$out/drape" "$edits" --no-edit-outputs --output "$out/resumed" \
  > "$out/resumed.log" 2>&1 || { cat "$out/resumed.log"; exit 1; }
grep -q "resuming from $out/drape/drape_state.h5" "$out/resumed.log" ||
  { cat "$out/resumed.log"; echo "the drape was not resumed"; exit 1; }
[ "$before" = "$(md5sum "$out/drape/result.h5" "$out/drape/summary.json")" ] ||
  { echo "the edit changed the drape's directory"; exit 1; }
"$sartor" edit "$root/cases/patterns/skirt.json" "$edits" "${case[@]}" --no-edit-outputs \
  --output "$out/fresh" > "$out/fresh.log" 2>&1 || { cat "$out/fresh.log"; exit 1; }
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
drape, resumed, fresh = (json.load(open(f"{out}/{d}/summary.json"))
                         for d in ("drape", "resumed", "fresh"))
assert resumed["options"]["material-bending-model"] == "discrete_shell", resumed["options"]
assert resumed["options"]["output"] == f"{out}/resumed", resumed["options"]["output"]
edit = resumed["edit"]
assert edit["drape_resumed_from"] == f"{out}/drape", edit["drape_resumed_from"]
assert edit["drape_from_scratch_cpu_s"] == drape["drape"]["cpu_s"] > 0, (edit, drape["drape"])
assert fresh["edit"]["drape_resumed_from"] == "", fresh["edit"]["drape_resumed_from"]
a, b = edit["steps"][0], fresh["edit"]["steps"][0]
for step in (a, b):
    assert step["resolve"]["converged"], step["resolve"]
for key in ("before", "resolved", "linear"):
    za, zb = a["lowest_point_z_m"][key], b["lowest_point_z_m"][key]
    assert abs(za - zb) < 1e-4, (key, za, zb)
for kind in ("unchanged", "linear"):
    ea, eb = a["error_against_resolved"][kind]["max_m"], b["error_against_resolved"][kind]["max_m"]
    assert abs(ea - eb) < 1e-4, (kind, ea, eb)
with open(f"{out}/resumed/petsc_options.txt") as echo:
    assert f"-output {out}/resumed\n" in echo.read(), "petsc_options.txt echoes another output"
print("lowest point re-solved: resumed", a["lowest_point_z_m"]["resolved"],
      "fresh", b["lowest_point_z_m"]["resolved"])
PY
# --edit-start geometric starts the re-solve from the thesis' route (cut off
# after one Newton iteration here: the start is what is checked).
status=0
"$sartor" edit "$out/drape" "$edits" --edit-start geometric --edit-max-newton 1 --no-edit-retry \
  --no-edit-outputs --output "$out/geometric" > "$out/geometric.log" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$out/geometric.log"; echo "status $status, not 1"; exit 1; }
/usr/bin/python3 - "$out/geometric/summary.json" <<'PY'
import json, sys
step = json.load(open(sys.argv[1]))["edit"]["steps"][0]
assert [a["start"] for a in step["attempts"]] == ["geometric"], step["attempts"]
assert "geometric" in step["start_energy_J"], step["start_energy_J"]
PY
refused() { # refused MESSAGE ARGS...: sartor edit exits with status 2 and MESSAGE
  local message=$1 status=0
  shift
  "$sartor" edit "$@" > "$out/refused.log" 2>&1 || status=$?
  [ "$status" = 2 ] || { cat "$out/refused.log"; echo "status $status, not 2: $*"; exit 1; }
  grep -q -- "$message" "$out/refused.log" ||
    { cat "$out/refused.log"; echo "no '$message': $*"; exit 1; }
}
refused "option --edge-length: $out/drape was draped with '0.08', not '0.06'" \
  "$out/drape" "$edits" --edge-length 0.06 --output "$out/bad"
refused "option --bending-model: $out/drape was draped with 'discrete_shell', not 'patch'" \
  "$out/drape" "$edits" --bending-model patch --output "$out/bad"
refused "option --output: $out/drape is the drape's own directory" \
  "$out/drape" "$edits" --output "$out/drape"
cp -r "$out/drape" "$out/changed"
/usr/bin/python3 - "$out/changed/summary.json" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))
summary["pattern_checksum"] = "0" * 16
json.dump(summary, open(sys.argv[1], "w"))
PY
refused "skirt.json has changed since it was draped into $out/changed" \
  "$out/changed" "$edits" --output "$out/bad"
rm "$out/changed/drape_state.h5"
refused "$out/changed: no drape_state.h5" "$out/changed" "$edits" --output "$out/bad"
mkdir -p "$out/empty"
refused "$out/empty: not a drape's output directory" "$out/empty" "$edits"
