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
# The same again sewn gradually (--sewing-tension 1 --sewing-time 0.5): the
# same assertions at the end, and at t = 0.1 s the seams are still open by
# more than 0.1 mm where the plain springs have closed them to 1e-8 m.
#   tube_on_cylinder.sh SARTOR CASES_DIR OUT_DIR
set -euo pipefail
sartor=$1 cases=$2 out=$3
/usr/bin/python3 -c "import h5py, numpy" 2> /dev/null || { echo "error: no h5py/numpy (./dev deps installs it)" >&2; exit 1; }
rm -rf "$out" && mkdir -p "$out"
"$sartor" run "$cases/tube_on_cylinder.yaml" --output "$out/tube" > "$out/tube.log"
"$sartor" run "$cases/tube_on_cylinder.yaml" --sewing-tension 1 --sewing-time 0.5 \
  --output "$out/sewn" > "$out/sewn.log"
/usr/bin/python3 - "$out" <<'PY'
import h5py, json, math, sys
import numpy as np
out = sys.argv[1]
failures = []
def check(condition, message):
    if not condition:
        failures.append(message)
nx, ny = 12, 6
front = (nx + 1) * (ny + 1)
def gap_at(run, time):
    # The two seams join the panels' first and last columns; which column of
    # the front meets which of the back is read off the start.
    with h5py.File(f"{out}/{run}/series.h5") as f:
        steps = f["steps"]
        x = {float(steps[k]["time"][()]): steps[k]["fields"]["position"][()] for k in steps}
    start, now = x[0.0], min(x.items(), key=lambda item: abs(item[0] - time))[1]
    rows = range(ny + 1)
    def gaps(p, a, b):
        return [np.linalg.norm(p[j * (nx + 1) + a] - p[front + j * (nx + 1) + b]) for j in rows]
    pairing = min([(0, 0), (0, nx)], key=lambda ab: max(gaps(start, *ab)))
    other = (nx - pairing[0], nx - pairing[1])
    return max(gaps(now, *pairing) + gaps(now, *other))
def check_run(run):
    s = json.load(open(f"{out}/{run}/summary.json"))
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
    v = [tuple(map(float, l.split()[1:4])) for l in open(f"{out}/{run}/final.obj") if l.startswith("v ")]
    check(len(v) == 2 * front, f"{len(v)} vertices")
    worst = 0.0
    for j in range(ny + 1):
        ring = [j * (nx + 1) + i for i in range(nx + 1)] + [front + j * (nx + 1) + i for i in range(nx + 1)]
        length = sum(math.dist(v[a], v[b]) for a, b in zip(ring, ring[1:] + ring[:1]))
        worst = max(worst, abs(length / 0.6 - 1.0))
        if j == ny // 2:
            middle = length
    check(worst < 1e-3, f"ring length off the panel widths by {worst} relative")
    print(f"{run}: {d['steps']} steps, {d['newton_iterations']} Newton iterations "
          f"(settle {d['settle']['newton_iterations']}); gap {gap:.2e} m; reaction {rz:.12g} N, "
          f"weight {weight:.12g} N; penetration {penetration:.2e} m; mid ring {middle:.9f} m "
          f"(worst ring {worst:.1e} relative)")
    return s
check_run("tube")
sewn = check_run("sewn")
check(sewn["seams"]["sewing_tension_N_per_m"] == 1.0 and sewn["seams"]["sewing_end_time_s"] == 0.5,
      f"sewing not recorded: {sewn['seams']}")
early = {run: gap_at(run, 0.1) for run in ("tube", "sewn")}
check(early["tube"] < 1e-8, f"plain springs: gap {early['tube']} m at t = 0.1 s")
check(early["sewn"] > 1e-4, f"sewn gradually: gap {early['sewn']} m at t = 0.1 s")
print(f"largest seam gap at t = 0.1 s: plain {early['tube']:.1e} m, sewn {early['sewn']:.1e} m")
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
