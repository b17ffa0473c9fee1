#!/usr/bin/env bash
# `sartor wrap` and `sartor drag` end to end on the samples of cases/wrap:
# the sleeve on its capsule arm, the tube skirt on the mannequin (coarse, for
# speed), the sleeve rewrapped by its cuff with two pushpins, then the
# sleeve's drag script; the sleeve at 8 cm edges (too long for the arm)
# wrapped and dragged with adaptive subdivision. The numbers in wrap.json and
# drag.json are checked against stated bounds (docs/wrapping.md).
#
#   wrap_cli.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASES_DIR WORKDIR" >&2; exit 2; }
sartor=$1 cases=$2 work=$3
rm -rf "$work" && mkdir -p "$work"

"$sartor" wrap "$cases/sleeve.json" "$cases/sleeve_marks.json" --output "$work/sleeve" --no-plot \
  > "$work/sleeve.log"
"$sartor" wrap "$cases/tube.json" "$cases/tube_marks.json" --edge-length 0.05 \
  --output "$work/tube" --no-plot > "$work/tube.log"
"$sartor" wrap "$cases/sleeve.json" "$cases/sleeve_rewrap_marks.json" --rewrap "$work/sleeve/wrapped.obj" \
  --output "$work/rewrap" --no-plot > "$work/rewrap.log"
"$sartor" drag "$work/sleeve/wrapped.obj" "$cases/sleeve_drags.yaml" --output "$work/drag" \
  --no-plot > "$work/drag.log"
"$sartor" wrap "$cases/sleeve.json" "$cases/sleeve_marks.json" --edge-length 0.08 --subdivide \
  --output "$work/coarse" --no-plot > "$work/coarse.log"
"$sartor" drag "$work/coarse/wrapped.obj" "$cases/sleeve_drags.yaml" --subdivide \
  --output "$work/coarse_drag" --no-plot > "$work/coarse_drag.log"

/usr/bin/python3 - "$work" <<'PYTHON'
import json, sys
work = sys.argv[1]
failures = []
def check(ok, what):
    if not ok:
        failures.append(what)
for name, mismatch_bound in (("sleeve", 0.015), ("tube", 0.03)):
    w = json.load(open("%s/%s/wrap.json" % (work, name)))
    check(w["mark_mismatch_m"]["max"] < mismatch_bound,
          "%s: mark mismatch %g m above %g m" % (name, w["mark_mismatch_m"]["max"], mismatch_bound))
    check(w["mark_mismatch_m"]["crossings"] > 10, "%s: too few mark crossings" % name)
    check(w["min_body_distance_m"] >= 0.0, "%s: a vertex inside the body" % name)
    ratio = w["edge_length_ratio"]
    check(0.5 < ratio["min"] and ratio["max"] < 2.0,
          "%s: edge length ratios %g..%g outside 0.5..2" % (name, ratio["min"], ratio["max"]))
# The bones: the capsule's axis; the mannequin's skeleton.
for name, bones in (("sleeve", 1), ("tube", 20)):
    b = json.load(open("%s/%s/wrap.json" % (work, name)))["bones"]
    check(b["count"] == bones and len(b["names"]) == bones,
          "%s: %d bones, not %d" % (name, b["count"], bones))
c = json.load(open("%s/coarse/wrap.json" % work))
split = c["split_edges"]
check(split > 0, "coarse sleeve: no edge split")
check(c["subdivision"]["splits"] - c["subdivision"]["merges"] == split,
      "coarse sleeve: splits - merges != split edges")
check(c["min_body_distance_m"] >= 0.0, "coarse sleeve: a vertex inside the body")
check(c["mark_mismatch_m"]["max"] < 0.02, "coarse sleeve: mark mismatch %g m" % c["mark_mismatch_m"]["max"])
cd = json.load(open("%s/coarse_drag/drag.json" % work))
check(cd["subdivision"]["split_edges"] > 0, "coarse drag: no edge split")
check(cd["min_body_distance_m"] >= 0.0, "coarse drag: a vertex inside the body")
check(abs(cd["drags"][0]["vertex_displacement_m"][0] - 0.05) < 1e-6, "coarse drag: the slide fell short")
r = json.load(open("%s/rewrap/wrap.json" % work))
check(r["rewrap"]["pin_motion_max_m"] < 1e-12, "rewrap: a pin moved %g m" % r["rewrap"]["pin_motion_max_m"])
check(r["rewrap"]["kept_vertices"] > 0, "rewrap: the pins kept nothing")
check(r["mark_mismatch_m"]["max"] < 0.015, "rewrap: mark mismatch %g m" % r["mark_mismatch_m"]["max"])
check(r["min_body_distance_m"] >= 0.0, "rewrap: a vertex inside the body")
d = json.load(open("%s/drag/drag.json" % work))
slide, turn = d["drags"]
check(abs(slide["vertex_displacement_m"][0] - 0.05) < 1e-6,
      "slide: the grabbed vertex moved %g m along the arm, not 0.05" % slide["vertex_displacement_m"][0])
check(turn["pin_motion_max_m"] < 1e-12, "turn: the pin moved %g m" % turn["pin_motion_max_m"])
rise = turn["vertex_displacement_m"][2]
check(0.025 < rise < 0.031, "turn: the grabbed vertex rose %g m, not about 0.03" % rise)
check(d["min_body_distance_m"] >= 0.0, "drag: a vertex inside the body")
if failures:
    sys.exit("wrap_cli: " + "; ".join(failures))
print("wrap_cli: sleeve, tube, rewrap, drags and the subdivided coarse sleeve within their bounds")
PYTHON
