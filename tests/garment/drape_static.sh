#!/usr/bin/env bash
# `sartor drape` by its default, the static minimiser, on a coarsely meshed
# garment (a case file of cases/garments): no time stepping (no dynamics in
# summary.json, no dynamics.csv), sewn in eight continuation stages, in static
# equilibrium (the residual force below 1e-5 of the weight, the body's
# reaction balancing the weight computed here from density and area), the
# seams closed, no vertex inside the body and none deeper than half the
# contact offset in the offset layer (what the adaptive penalty promises),
# and the garment resting on the body rather than squeezing it (the body's
# normal force below 3 times the weight; static friction can hold a
# garment pulled down over the body). The Newton
# count has a generous bound (the dynamic relaxation took about 3,000 on
# these garments; the minimiser about 100 to 400).
#
#   drape_static.sh SARTOR PATTERN CASE OUT_DIR SEAMS [DRAPE_OPTION ...]
set -euo pipefail
[ $# -ge 5 ] || { echo "usage: $0 SARTOR PATTERN CASE OUT_DIR SEAMS [DRAPE_OPTION ...]" >&2; exit 2; }
sartor=$1 pattern=$2 case=$3 dir=$4 seams=$5
shift 5
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
"$sartor" drape "$pattern" -options_file_yaml "$case" "$@" --no-plot --output "$dir" | tee "$dir.log"
grep -q "static minimiser, converged" "$dir.log"
for f in final.obj result.h5 summary.json; do
  [ -s "$dir/$f" ] || { echo "drape_static: $dir/$f missing" >&2; exit 1; }
done
[ ! -e "$dir/dynamics.csv" ] || { echo "drape_static: time stepping ran" >&2; exit 1; }
# The drape's Hessians are symmetric: on one rank MUMPS's LDL^T factorises them.
grep -qx -- "-pc_type cholesky" "$dir/petsc_options.txt" ||
  { echo "drape_static: the symmetric Newton systems were not factorised by LDL^T" >&2; exit 1; }
"$python" - "$dir" "$seams" <<'PY'
import json, math, os, sys
d, seams = sys.argv[1], int(sys.argv[2])
s = json.load(open(os.path.join(d, "summary.json")))
drape = s["drape"]
assert "dynamics" not in s, "the static drape stepped in time"
assert s["converged"] and drape["converged"] and drape["equilibrium_checked"], s["solver"]
assert drape["method"] == "minimise" and s["solver"]["method"] == "minimise", s["solver"]
minimiser = s["solver"]["minimiser"]
assert minimiser["sewing_stages"] == 8, minimiser
assert s["solver"]["newton_iterations"] < 1500, s["solver"]
assert s["seams"]["seams"] == seams, s["seams"]
assert drape["largest_seam_gap_m"] < 5e-4, drape
offset = drape["contact_offset_m"]
assert not drape["vertex_inside_body"], drape
assert drape["max_penetration_m"] < 0.5 * offset, drape
assert abs(drape["deepest_vertex_relative_to_offset"] - drape["max_penetration_m"] / offset) < 1e-9
weight = math.hypot(*drape["weight_N"])
assert abs(weight - 9.80665 * 0.25 * drape["material_area_m2"]) < 1e-9 * weight, drape
assert drape["residual_force_N"] < 1e-5 * weight, drape
assert drape["relative_imbalance"] < 1e-5, drape
assert abs(drape["body_reaction_N"][2] - weight) < 1e-5 * weight, drape
# The parts of the certificate static drapes pass today: friction ends
# consistent (the contact rounds repeat until updating the anchors leaves
# the state in equilibrium), so the equilibrium with the anchors as updated
# and Coulomb's cone at every contact pass; no edge passes through the body
# since edges carry contact samples (docs/contact.md).
c = s["certificate"]
assert drape["certificate"] == c["verdict"], drape
assert minimiser["friction_consistent"], minimiser
assert minimiser["anchored_residual_N"] < 1e-5 * s["certificate"]["equilibrium"]["reference_force_N"]
for part in ("equilibrium", "depth", "edges", "seams", "coulomb", "placement"):
    assert c[part]["passed"], (part, c[part])
assert c["coulomb"]["outside_cone"] == 0 and c["coulomb"]["pulling"] == 0, c["coulomb"]
assert c["stability"]["assessed"] and c["stability"]["negative_directions"] == 0, c["stability"]
body = s["contact"]["bodies"][0]
# It touches the body: by vertices, or by the samples of its edges (which
# may hold every vertex off the offset layer on the convex shoulders).
assert body["contacting_vertices"] + body["contacting_edge_samples"] > 0, body
# The result's friction utilisation is the certificate's cone test per
# vertex: the friction over mu_s times the normal force with the vertex's
# share of its edges' samples (which bounds its anchor), so it is within the
# cone's 5 % tolerance everywhere, and not zero where friction acts (the
# vertices the samples hold off the body included).
import h5py
with h5py.File(os.path.join(d, "result.h5"), "r") as f:
    friction = f["/fields/friction_force"][:]
    utilisation = f["/fields/friction_utilisation"][:]
assert utilisation.max() <= 1.05, f"friction utilisation up to {utilisation.max()}"
held = friction > 1e-6 * weight
assert held.any() and (utilisation[held] > 0).all(), \
    f"{int((utilisation[held] == 0).sum())} of {int(held.sum())} vertices with friction have none"
normal = math.hypot(*body["normal_force_N"])
assert normal < 3 * weight, f"the body presses on the garment with {normal} N (weight {weight} N)"
print("drape_static: %d triangles, %d Newton iterations, gap %.2e m, deepest %.2f of the offset, "
      "residual %.1e of the weight" % (s["mesh"]["triangles"], s["solver"]["newton_iterations"],
      drape["largest_seam_gap_m"], drape["deepest_vertex_relative_to_offset"],
      drape["residual_relative_to_weight"]))
PY
