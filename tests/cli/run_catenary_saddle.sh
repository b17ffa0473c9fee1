#!/usr/bin/env bash
# The flat-start catenary (cases/fe/catenary_flat_start.yaml): Newton from the
# flat strip by SNES's Newton (--static-solver snes) ends on the compressed
# arch. Without escapes `sartor run` must report it as a saddle (negative
# directions of the true Hessian, closing line, exit status); with them it
# must find the hanging catenary, certified stable; and the static minimiser
# (the default) must find it too. Both sags must match the inextensible
# catenary's closed form:
#     L = 2 a sinh(s / (2 a)),
#     sag = a (cosh(s / (2 a)) - 1),
# L = 1 m, s = 0.6 m (solved for a here by bisection).
#   run_catenary_saddle.sh SARTOR CASE.yaml WORKDIR
set -euo pipefail
sartor=$1 case=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
status=0
"$sartor" run "$case" --static-solver snes --escape-saddles 0 --no-plot --output "$work/arch" \
  > "$work/arch.log" 2>&1 ||
  status=$?
# 1: a computation that did not reach its goal (2 would be a bad input).
[ "$status" -eq 1 ] || { cat "$work/arch.log" >&2; echo "exit status $status, expected 1" >&2; exit 1; }
grep -q "certificate: saddle" "$work/arch.log" || { cat "$work/arch.log" >&2; exit 1; }
grep -q "ended on a saddle" "$work/arch.log" || { cat "$work/arch.log" >&2; exit 1; }
"$sartor" run "$case" --static-solver snes --no-plot --output "$work/hanging" > "$work/hanging.log"
grep -q "certificate: certified" "$work/hanging.log" || { cat "$work/hanging.log" >&2; exit 1; }
"$sartor" run "$case" --no-plot --output "$work/minimised" > "$work/minimised.log"
grep -q "certificate: certified" "$work/minimised.log" || { cat "$work/minimised.log" >&2; exit 1; }
/usr/bin/python3 - "$work" <<'PY'
import json, math, sys
work = sys.argv[1]
failures = []
arch = json.load(open(f"{work}/arch/summary.json"))
hanging = json.load(open(f"{work}/hanging/summary.json"))
a, h = arch["certificate"], hanging["certificate"]
if arch["converged"] or not a["stability"]["saddle"] or a["stability"]["negative_directions"] < 1:
    failures.append(f"arch: converged {arch['converged']}, stability {a['stability']}")
if not a["equilibrium"]["passed"]:
    failures.append("arch: not even stationary")
if not (hanging["converged"] and h["certified"] and h["stability"]["negative_directions"] == 0):
    failures.append(f"hanging: converged {hanging['converged']}, certificate {h['verdict']}")
if h["saddle_escapes"] < 1:
    failures.append("hanging: no escape was taken")
if not hanging["energy_J"]["total"] < arch["energy_J"]["total"]:
    failures.append("the hanging strip does not store less energy than the arch")
# The inextensible catenary of length L over span s.
L, s = 1.0, 0.6
lo, hi = 0.01, 10.0  # 2 a sinh(s / 2a) falls from huge to s as a grows
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if 2 * mid * math.sinh(s / (2 * mid)) > L:
        lo = mid
    else:
        hi = mid
a_cat = 0.5 * (lo + hi)
sag = a_cat * (math.cosh(s / (2 * a_cat)) - 1)
measured = -hanging["probe"]["displacement_m"][2]
minimised = json.load(open(f"{work}/minimised/summary.json"))
m = minimised["certificate"]
if not (minimised["converged"] and m["certified"] and m["stability"]["negative_directions"] == 0):
    failures.append(f"minimised: converged {minimised['converged']}, certificate {m['verdict']}")
# 40 elements, and the cloth stretches by 1e-4 under its tension.
for name, value in (("escaped", measured), ("minimised", -minimised["probe"]["displacement_m"][2])):
    if abs(value - sag) > 0.01 * sag:
        failures.append(f"{name}: sag {value} m, catenary {sag} m")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"arch: {a['stability']['negative_directions']} negative directions; "
      f"hanging sag {measured:.5f} m, catenary {sag:.5f} m")
PY
