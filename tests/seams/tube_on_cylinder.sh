#!/bin/bash
# cases/seams/tube_on_cylinder.yaml end to end: two 30 x 20 cm panels, 12 x 6
# cells each, are sewn into a tube around a horizontal bar (radius 8 cm, the
# tube's 0.3/pi = 9.5 cm) and fall onto it in dynamics with kinetic damping;
# the settle solve ends it. Asserts: converged; seams closed (gap < 1e-6 m);
# no vertex inside the bar nor deeper than the contact offset; the bar alone
# carries the tube's weight (to 1e-6 relative, no horizontal reaction); every
# ring of the sewn tube (a row of the back panel, then the same row of the
# front panel, closed by the two seams) is as long as the two panel widths,
# 0.6 m, to 1e-3 relative.
#   tube_on_cylinder.sh SARTOR CASES_DIR OUT_DIR
set -euo pipefail
sartor=$1 cases=$2 out=$3
command -v /usr/bin/python3 > /dev/null || exit 77
rm -rf "$out" && mkdir -p "$out"
"$sartor" run "$cases/tube_on_cylinder.yaml" --output "$out/tube" > "$out/tube.log"
/usr/bin/python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
failures = []
def check(condition, message):
    if not condition:
        failures.append(message)
s = json.load(open(f"{out}/tube/summary.json"))
d, c = s["dynamics"], s["contact"]
bar = c["bodies"][0]
check(s["converged"] and d["completed"] and d["settle"]["converged"],
      f"not converged: {d['reason']}, settle {d['settle']}")
check(s["seams"]["seams"] == 2 and s["seams"]["springs"] == 14, f"seams {s['seams']}")
gap = s["seams"]["largest_gap_m"]
check(gap < 1e-6, f"seam gap {gap} m")
penetration = c["max_penetration_m"]
check(penetration < c["offset_m"], f"penetration {penetration} m, offset {c['offset_m']} m")
check(bar["min_distance_m"] > 0.0, f"a vertex inside the bar ({bar['min_distance_m']} m)")
weight = 0.2 * 2 * 0.3 * 0.2 * 9.80665  # kg/m^2 x two panels' m^2 x m/s^2
rz = bar["reaction_N"][2]
check(abs(rz - weight) < 1e-6 * weight, f"reaction {rz} N, weight {weight} N")
check(max(abs(bar["reaction_N"][0]), abs(bar["reaction_N"][1])) < 1e-6 * weight,
      f"horizontal reaction {bar['reaction_N']}")
v = [tuple(map(float, l.split()[1:4])) for l in open(f"{out}/tube/final.obj") if l.startswith("v ")]
nx, ny = 12, 6
front = (nx + 1) * (ny + 1)
check(len(v) == 2 * front, f"{len(v)} vertices")
worst = 0.0
for j in range(ny + 1):
    ring = [j * (nx + 1) + i for i in range(nx + 1)] + [front + j * (nx + 1) + i for i in range(nx + 1)]
    length = sum(math.dist(v[a], v[b]) for a, b in zip(ring, ring[1:] + ring[:1]))
    worst = max(worst, abs(length / 0.6 - 1.0))
    if j == ny // 2:
        middle = length
check(worst < 1e-3, f"ring length off the panel widths by {worst} relative")
print(f"tube on bar: {d['steps']} steps, {d['newton_iterations']} Newton iterations "
      f"(settle {d['settle']['newton_iterations']}); gap {gap:.2e} m; reaction {rz:.12g} N, "
      f"weight {weight:.12g} N; penetration {penetration:.2e} m; mid ring {middle:.9f} m "
      f"(worst ring {worst:.1e} relative)")
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
