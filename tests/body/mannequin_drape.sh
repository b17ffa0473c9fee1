#!/usr/bin/env bash
# cases/bodies/mannequin.yaml end to end: a 30 x 30 cm cloth (8 x 8) falls on
# the built-in mannequin's head in dynamics with kinetic damping and settles.
# Asserts: converged; no vertex inside the body nor deeper than the contact
# offset; the mannequin alone carries the cloth's weight (to 1e-6 relative, no
# horizontal reaction); the cloth hangs over the head (its edges below the
# crown).
#   mannequin_drape.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASES_DIR WORKDIR" >&2; exit 2; }
sartor=$1 cases=$2 work=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$cases/mannequin.yaml" --output "$work/drape" > "$work/drape.log"
"$python" - "$work" <<'PY'
import json, sys
work = sys.argv[1]
failures = []
def check(condition, message):
    if not condition:
        failures.append(message)
s = json.load(open(f"{work}/drape/summary.json"))
d, c = s["dynamics"], s["contact"]
body = c["bodies"][0]
check(s["converged"] and d["completed"] and d["settle"]["converged"],
      f"not converged: {d['reason']}, settle {d['settle']}")
check(c["max_penetration_m"] < c["offset_m"],
      f"penetration {c['max_penetration_m']} m, offset {c['offset_m']} m")
check(body["min_distance_m"] > 0.0, f"a vertex inside the mannequin ({body['min_distance_m']} m)")
weight = 0.25 * 0.3 * 0.3 * 9.80665  # kg/m^2 x m^2 x m/s^2
rz = body["reaction_N"][2]
check(abs(rz - weight) < 1e-6 * weight, f"reaction {rz} N, weight {weight} N")
check(max(abs(body["reaction_N"][0]), abs(body["reaction_N"][1])) < 1e-6 * weight,
      f"horizontal reaction {body['reaction_N']}")
z = [float(l.split()[3]) for l in open(f"{work}/drape/final.obj") if l.startswith("v ")]
check(min(z) < 1.70, f"the cloth does not hang over the head: lowest z {min(z)} m")
print(f"mannequin drape: {d['steps']} steps, {d['newton_iterations']} Newton iterations "
      f"(settle {d['settle']['newton_iterations']}); reaction {rz:.12g} N, weight {weight:.12g} N; "
      f"penetration {c['max_penetration_m']:.2e} m; lowest z {min(z):.4f} m")
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
