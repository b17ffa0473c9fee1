#!/usr/bin/env bash
# `sartor converge` from the command line on small Hencky meshes: --help, the
# files it writes (CSV header and rows, JSON, per-level results, the plot when
# matplotlib is there), self-convergence without --reference, the energy
# quantity, option errors, and the same study on 2 MPI ranks.
#   converge_cli.sh SARTOR CASE.yaml WORKDIR [MPIEXEC [MPIEXEC FLAGS...]]
set -euo pipefail
sartor=$1 case=$2 work=$3
shift 3
python=/usr/bin/python3
"$python" -c "import json" 2> /dev/null || { echo "error: no $python (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$sartor" converge --help > "$work/help.txt"
grep -q "usage: sartor converge CASE.yaml --levels N" "$work/help.txt" || fail "help: usage"
grep -q -- "--reference VALUE" "$work/help.txt" || fail "help: --reference"
grep -q -- "--mesh-snap-boundary" "$work/help.txt" || fail "help: case options"

# Three levels from a 2-ring disk (24 to 384 triangles), no reference.
plot=(--no-plot)
if "$python" -c "import numpy, matplotlib" 2> /dev/null; then plot=(); fi
small=(--mesh-rings 2 -snes_linesearch_type l2)
"$sartor" converge "$case" --levels 3 "${small[@]}" "${plot[@]}" --output "$work/self" \
  > "$work/self.log"
grep -q "no reference: self-convergence" "$work/self.log" || fail "self.log: header"
grep -q "self-convergence, levels 0-1-2" "$work/self.log" || fail "self.log: orders"
for f in convergence.csv convergence.json petsc_options.txt level_0/summary.json \
  level_2/summary.json level_2/result.h5 level_2/result.xmf level_2/final.obj; do
  [ -s "$work/self/$f" ] || fail "missing $work/self/$f"
done
if [ ${#plot[@]} -eq 0 ]; then
  [ -s "$work/self/convergence.png" ] || fail "missing convergence.png"
fi
[ "$(head -1 "$work/self/convergence.csv")" = \
  "level,h,triangles,dofs,value,error,newton_iterations,solve_time_s" ] || fail "CSV header"

# The energy of the same meshes, with a (made-up) reference value.
"$sartor" converge "$case" --levels 2 "${small[@]}" --quantity energy --reference 1e-3 \
  --no-plot --output "$work/energy" > "$work/energy.log"

"$python" - "$work" <<'PY'
import csv, json, math, sys
work = sys.argv[1]
failures = []
s = json.load(open(f"{work}/self/convergence.json"))
rows = list(csv.DictReader(open(f"{work}/self/convergence.csv")))
if len(rows) != 3 or len(s["rows"]) != 3:
    failures.append(f"{len(rows)} CSV rows, {len(s['rows'])} JSON rows")
if [int(r["triangles"]) for r in rows] != [24, 96, 384]:
    failures.append(f"triangles {[r['triangles'] for r in rows]}")
if rows[0]["error"] != "nan" or s["rows"][0]["error"] is not None:
    failures.append("level 0 of a self-convergence study has no error")
if s["reference"] is not None or not s["complete"] or s["command"] != "converge":
    failures.append("reference/complete/command")
h = [float(r["h"]) for r in rows]
if not all(abs(h[k] / h[k + 1] - 2) < 0.15 for k in range(2)):  # snapping: not exactly 2
    failures.append(f"h does not halve: {h}")
v = [float(r["value"]) for r in rows]
change = abs(v[2] - v[1])
if abs(float(rows[2]["error"]) - change) > 1e-15:
    failures.append("error column is not the change from the previous level")
t = s["self_convergence"][0]
p = math.log(abs(v[1] - v[0]) / abs(v[2] - v[1])) / math.log(h[0] / h[1])
if t["levels"] != [0, 1, 2] or (t["monotone"] and abs(t["order"] - p) > 1e-12):
    failures.append(f"self-convergence entry {t}, order should be {p}")
level = json.load(open(f"{work}/self/level_2/summary.json"))
if level["probe"]["displacement_m"][2] != v[2] or level["level"] != 2 or level["mesh_refine"] != 2:
    failures.append("level_2/summary.json disagrees with the table")
if abs(level["h"] - h[2]) > 1e-15 or not level["converged"]:
    failures.append("level_2/summary.json: h or converged")
e = json.load(open(f"{work}/energy/convergence.json"))
if e["quantity"]["name"] != "energy" or e["quantity"]["unit"] != "J":
    failures.append(f"energy quantity {e['quantity']}")
for k, row in enumerate(e["rows"]):
    total = json.load(open(f"{work}/energy/level_{k}/summary.json"))["energy_J"]["total"]
    if row["value"] != total or abs(row["error"] - abs(total - 1e-3)) > 1e-18:
        failures.append(f"energy row {k}: {row['value']} vs {total}")
if len(e["orders"]) != 1 or e["orders"][0]["levels"] != [0, 1]:
    failures.append(f"energy orders {e['orders']}")
if failures:
    print("FAIL:", "; ".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"self-convergence values {v}, h {h}")
PY

# Option errors: a clean one-line message and exit status 1.
expect_error() {
  local pattern=$1
  shift
  if "$sartor" converge "$case" "$@" --no-plot --output "$work/bad" > "$work/bad.log" 2>&1; then
    fail "succeeded: $*"
  fi
  grep -q -- "$pattern" "$work/bad.log" || { cat "$work/bad.log" >&2; fail "message for: $*"; }
}
expect_error "option --quantity: unknown quantity 'bogus'" --quantity bogus
expect_error "option --levels: must lie in 1..12, got 0" --levels 0
grep -v '^probe:' "$case" > "$work/no_probe.yaml"
case_without_probe=$work/no_probe.yaml
if "$sartor" converge "$case_without_probe" --levels 1 --no-plot --output "$work/bad" \
  > "$work/bad.log" 2>&1; then
  fail "succeeded without --probe"
fi
grep -q -- "--quantity probe_z needs --probe X,Y,Z" "$work/bad.log" || fail "no-probe message"
expect_error "option --mesh-snap-boundary applies to --mesh disk only" --mesh rectangle \
  --levels 1

# Two ranks give the serial numbers.
if [ $# -ge 1 ] && [ -n "$1" ]; then
  mpiexec=$1
  shift
  "$mpiexec" -n 2 "$@" "$sartor" converge "$case" --levels 3 "${small[@]}" --no-plot \
    --output "$work/mpi" > "$work/mpi.log"
  "$python" - "$work" <<'PY'
import json, sys
work = sys.argv[1]
s = json.load(open(f"{work}/self/convergence.json"))
p = json.load(open(f"{work}/mpi/convergence.json"))
if p["mpi_ranks"] != 2:
    sys.exit(f"FAIL: {p['mpi_ranks']} ranks")
for a, b in zip(s["rows"], p["rows"]):
    if abs(a["value"] - b["value"]) > 1e-9 * abs(a["value"]) or a["dofs"] != b["dofs"]:
        sys.exit(f"FAIL: level {a['level']}: serial {a['value']}, 2 ranks {b['value']}")
print("2 ranks agree with 1")
PY
fi
echo "converge_cli: ok"
