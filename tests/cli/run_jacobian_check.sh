#!/usr/bin/env bash
# -snes_test_jacobian on real cases through `sartor run`: the assembled
# Jacobian must match PETSc's finite-difference Jacobian of the residual,
# ||J - Jfd||_F / ||J||_F below 1e-5 at every Newton iteration (round-off of
# the differences is ~1e-7 here). Cases: the hanging sheet with discrete-shell
# bending; St. Venant-Kirchhoff with Poisson coupling and quadratic bending;
# the square membrane under follower pressure (non-symmetric Jacobian); one
# step of implicit dynamics (inertia and damping terms). Then the hanging
# sheet must also converge with the trust-region Newton (-snes_type newtontr).
#   run_jacobian_check.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
sartor=$1 cases=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
small=(--mesh-nx 4 --mesh-ny 4)

check() { # NAME CASE ARGS...
  local name=$1 case=$2
  shift 2
  "$sartor" run "$cases/$case" "${small[@]}" "$@" --output "$work/$name" -snes_test_jacobian \
    > "$work/$name.log" 2>&1 || { cat "$work/$name.log" >&2; echo "$name: run failed" >&2; exit 1; }
  awk -v name="$name" '
    /\|\|J - Jfd\|\|_F\/\|\|J\|\|_F = / {
      value = $0; sub(/.*\|\|J - Jfd\|\|_F\/\|\|J\|\|_F = /, "", value); sub(/,.*/, "", value)
      value += 0; count++; if (value > worst) worst = value
    }
    END {
      if (count == 0) { print name ": no Jacobian test in the output" > "/dev/stderr"; exit 1 }
      printf "%s: %d Jacobian tests, largest ||J - Jfd||_F/||J||_F = %.3g\n", name, count, worst
      if (worst > 1e-5) { print name ": Jacobian differs from finite differences" > "/dev/stderr"; exit 1 }
    }' "$work/$name.log"
}

# (--static-solver snes: the static minimiser, run's default, does not go
# through SNES, whose -snes_test_jacobian this is.)
check hanging_sheet_bending hanging_sheet.yaml --bending-stiffness 1e-3 --static-solver snes
check stvk_poisson hanging_sheet.yaml --membrane-model stvk --poisson 0.3 --bending-model quadratic \
  --static-solver snes
check follower_pressure square_membrane_pressure.yaml --load-steps 1 --static-solver snes
check dynamic_step hanging_sheet_dynamic.yaml --time-end 0.02 --damping 2

# (--no-certificate: the flat sheet both Newtons reach is a saddle, which
# the certificate reports and pushes off; here only the solver is tested.)
"$sartor" run "$cases/hanging_sheet.yaml" --mesh-nx 10 --mesh-ny 10 --no-certificate --static-solver snes \
  --output "$work/newtontr" -snes_type newtontr > "$work/newtontr.log" 2>&1 || { cat "$work/newtontr.log" >&2; exit 1; }
/usr/bin/python3 - "$work" <<'PY' || exit 1
import json, sys
s = json.load(open(f"{sys.argv[1]}/newtontr/summary.json"))
weight = 0.2 * 9.80665
print(f"newtontr: {s['solver']['reason']} after {s['solver']['newton_iterations']} iterations")
if not s["converged"] or abs(s["pin_reaction_N"][2] - weight) > 1e-6 * weight:
    sys.exit("newtontr did not converge to the hanging sheet's equilibrium")
PY
