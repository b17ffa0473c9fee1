#!/usr/bin/env bash
# The static drape of drape_static.sh (certified, in equilibrium, on the
# body) with --contact-penalty-onset ONSET, which summary.json must report;
# and the law must reach the contact: the same case without the option ends
# elsewhere (the onset changes every contact force below its band, so no
# drape lands on the plain law's equilibrium to round-off).
#
#   drape_penalty_onset.sh SARTOR PATTERN CASE OUT_DIR SEAMS ONSET
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: $0 SARTOR PATTERN CASE OUT_DIR SEAMS ONSET" >&2; exit 2; }
sartor=$1 pattern=$2 case=$3 dir=$4 seams=$5 onset=$6
"$(dirname "${BASH_SOURCE[0]}")/drape_static.sh" "$sartor" "$pattern" "$case" "$dir" "$seams" \
  --contact-penalty-onset "$onset"
"$sartor" drape "$pattern" -options_file_yaml "$case" --no-plot --output "$dir.plain" \
  > "$dir.plain.log"
/usr/bin/python3 - "$dir" "$onset" <<'PY'
import json, sys
d, onset = sys.argv[1], float(sys.argv[2])
banded, plain = (json.load(open(p + "/summary.json")) for p in (d, d + ".plain"))
assert banded["contact"]["penalty_onset"] == onset, banded["contact"]
assert plain["contact"]["penalty_onset"] == 0.0, plain["contact"]

def vertices(run):
    with open(run + "/final.obj") as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]

apart = max(max(abs(p - q) for p, q in zip(u, v)) for u, v in zip(vertices(d), vertices(d + ".plain")))
print("drape_penalty_onset: onset %g and the plain law's drapes %.2e m apart" % (onset, apart))
assert apart > 1e-6, "the onset left the drape where the plain law puts it"
PY
