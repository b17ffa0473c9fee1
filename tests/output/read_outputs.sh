#!/usr/bin/env bash
# Every output file of a small dynamic run, a creep run, a short drape and a
# sheet on a plane, read with meshio and h5py (check_outputs.py) and ParaView
# (check_paraview.py), the OBJ files imported into Blender (check_blender.py):
# units, ids, material uv,
# clean times, the moving geometry of the time series, OBJ groups; and
# the pictures the commands draw by default; the contact pressure of the
# sheet on the plane (check_vertex_loads.py).
#   read_outputs.sh SARTOR CASES_DIR WORKDIR
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 SARTOR CASES_DIR WORKDIR" >&2; exit 2; }
sartor=$1 cases=$2 work=$3
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$work" && mkdir -p "$work"
"$sartor" run "$cases/fe/hanging_sheet_dynamic.yaml" --mesh-nx 6 --mesh-ny 6 --time-end 0.3 \
  --output-interval 0.1 --output "$work/run" > "$work/run.log"
"$sartor" run "$cases/creep/strip.yaml" --time-end 600 --output-interval 300 \
  --output "$work/creep" > "$work/creep.log"
"$sartor" drape "$cases/patterns/skirt.json" --edge-length 0.08 --time-end 0.02 \
  --sewing-time 0.01 -settle false --output "$work/drape" > "$work/drape.log"
"$sartor" run "$here/sheet_on_plane.yaml" --output "$work/plane" > "$work/plane.log"
# Pictures by default.
for f in run/result.png creep/result.png drape/drape.png; do
  [ -s "$work/$f" ] || { echo "read_outputs: $work/$f missing" >&2; exit 1; }
done
# Not skipped without meshio or h5py: /usr/bin/python3 must have both
# (Debian python3-meshio, python3-h5py; ./dev deps installs them).
/usr/bin/python3 "$here/check_outputs.py" run:"$work/run" creep:"$work/creep" \
  drape:cotton_twill:skirt_front,skirt_back:"$work/drape"
/usr/bin/python3 "$here/check_vertex_loads.py" "$work/plane"
# ParaView (Debian's python3-paraview) opens them too.
/usr/bin/python3 "$here/check_paraview.py" run:"$work/run" creep:"$work/creep" \
  drape:"$work/drape" contact:"$work/plane"
# Blender (Debian's blender) imports the OBJ files: vertices, UVs, panels.
blender -b --factory-startup --python-exit-code 1 --python "$here/check_blender.py" -- \
  "$work"/run/final.obj "$work"/creep/final.obj "$work"/drape/*.obj > "$work/blender.log" 2>&1 ||
  { cat "$work/blender.log" >&2; exit 1; }
