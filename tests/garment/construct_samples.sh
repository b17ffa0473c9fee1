#!/usr/bin/env bash
# `sartor construct` on the sample garments: the files it writes, and
# seams.json consistent with garment.obj (every seam found is in it; the
# T-shirt's pocket on three T-seams).
#
#   construct_samples.sh SARTOR SAMPLES_DIR OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR SAMPLES_DIR OUT_DIR" >&2; exit 2; }
sartor=$1 samples=$2 out=$3
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
for name in tshirt dress; do
  dir="$out/construct_$name"
  rm -rf "$dir"
  "$sartor" construct "$samples/$name.json" --output "$dir" --edge-length 0.04
  for f in garment.obj seams.json construct.json pattern_seams.svg placement.svg; do
    [ -s "$dir/$f" ] || { echo "construct_samples: $dir/$f missing" >&2; exit 1; }
  done
  "$python" - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]
seams = json.load(open(os.path.join(d, "seams.json")))["seams"]
summary = json.load(open(os.path.join(d, "construct.json")))
nv = sum(1 for row in open(os.path.join(d, "garment.obj")) if row.startswith("v "))
assert nv == summary["mesh"]["vertices"], (nv, summary["mesh"])
assert len(seams) == len(summary["seams"])
for s in seams:
    assert set(s) - {"t_seam"} == {"name", "a", "b", "reverse", "certainty"}, s
    assert 0 < s["certainty"] <= 1
    assert all(0 <= v < nv for v in s["a"] + s["b"])
t_seams = sum(s.get("t_seam", False) for s in seams)
assert t_seams == (3 if d.endswith("tshirt") else 0), t_seams
print(f"construct_samples: {d}: {len(seams)} seams ({t_seams} T-seams), {nv} vertices")
PY
done
