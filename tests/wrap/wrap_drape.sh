#!/usr/bin/env bash
# `sartor wrap --drape`: the sample sleeve wrapped coarsely on its arm and
# draped from there (drape's static minimiser). The drape must be certified
# and leave the sleeve around the arm: every vertex outside the capsule and
# within 5 cm of its surface (the capsule's distance computed here).
#
#   wrap_drape.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASES_DIR WORKDIR" >&2; exit 2; }
sartor=$1 cases=$2 work=$3
rm -rf "$work" && mkdir -p "$work"

"$sartor" wrap "$cases/sleeve.json" "$cases/sleeve_marks.json" --edge-length 0.05 --drape \
  --output "$work/sleeve" --no-plot > "$work/sleeve.log"

/usr/bin/python3 - "$work/sleeve/drape" <<'PYTHON'
import json, math, sys
directory = sys.argv[1]
summary = json.load(open(directory + "/summary.json"))
if not summary["converged"]:
    sys.exit("wrap_drape: the drape did not converge")
if summary["certificate"]["verdict"] != "certified":
    sys.exit("wrap_drape: the drape is not certified: %s" % summary["certificate"]["verdict"])
# The arm of cases/wrap/sleeve_marks.json: capsule from (0,0,1.2) to (0.6,0,1.2), r = 0.05.
def arm_distance(x, y, z):
    t = min(max(x / 0.6, 0.0), 1.0)
    return math.sqrt((x - 0.6 * t) ** 2 + y ** 2 + (z - 1.2) ** 2) - 0.05
distances = [arm_distance(*map(float, line.split()[1:4]))
             for line in open(directory + "/final.obj") if line.startswith("v ")]
if min(distances) < 0.0 or max(distances) > 0.05:
    sys.exit("wrap_drape: the draped sleeve is %g..%g m from the arm, not 0..0.05"
             % (min(distances), max(distances)))
print("wrap_drape: certified; the sleeve is %.4f..%.4f m from the arm"
      % (min(distances), max(distances)))
PYTHON
