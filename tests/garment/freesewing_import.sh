#!/usr/bin/env bash
# FreeSewing's own SVG output (cases/import/freesewing/, docs/freesewing.md)
# through `sartor import` and `sartor construct`, and with DRAPE through a
# coarse `sartor drape`:
# * Penelope (pencil skirt): the front unfolded, the back cut twice; every
#   dart found (2 per back piece, 4 in the unfolded front) and sewn leg to
#   leg, no dart leg in any other seam or unseamed, the centre back sewn
#   between the twins, the two side seams each pairing the front with a back
#   piece along the full side (equal lengths, vertical), the waistband left
#   out by the tag file; 11 seams in all.
# * Aaron (tank top): front and back unfolded, hung from the shoulders: two
#   side seams and two shoulder seams (lines at the top, above the chest),
#   4 seams in all.
# * Bella (bodice block): imported and its darts sewn: the front's waist
#   darts (37 degrees wide: the tag file's max_dart_angle_deg 40) and side
#   bust darts, mirrored, and each back piece's waist dart; 6 dart seams.
#   (TAGCON's shoulder and side seams of Bella are not right: not checked.)
# The drapes (drape: 8 cm triangles, as cases/garments/*_coarse.yaml;
# certified: *_certified.yaml, 4 cm), each on the mannequin sized to the
# measurement set the pattern was drafted for (cisFemaleAdult36) with
# friction, must end on the body (drape.outcome), with no vertex inside it,
# the seams closed and the certificate "certified".
#
#   freesewing_import.sh SARTOR CASES_DIR OUT_DIR [drape|certified]
set -euo pipefail
[ $# -eq 3 ] || [ $# -eq 4 ] || { echo "usage: $0 SARTOR CASES_DIR OUT_DIR [drape|certified]" >&2; exit 2; }
sartor=$1 cases=$2 dir=$3 drape=${4:-}
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$dir"
mkdir -p "$dir"
for design in penelope aaron bella; do
  "$sartor" import "$cases/${design}_cisFemaleAdult36.svg" --tags "$cases/${design}_tags.json" \
    --output "$dir/$design.json" | tee "$dir/$design.import.log"
  "$sartor" construct "$dir/$design.json" --output "$dir/${design}_construct" | tee "$dir/$design.construct.log"
done
grep -q "wrote $dir/penelope.json: 3 panels in 2 packs, valid" "$dir/penelope.import.log"
grep -q "piece 'waistband': left out" "$dir/penelope.import.log"
grep -q "wrote $dir/aaron.json: 2 panels in 2 packs, valid" "$dir/aaron.import.log"
grep -q "wrote $dir/bella.json: 3 panels in 2 packs, valid" "$dir/bella.import.log"
"$python" - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]

def load(design):
    pattern = json.load(open(os.path.join(d, design + ".json")))
    c = json.load(open(os.path.join(d, design + "_construct", "construct.json")))
    return pattern, c, {l["id"]: l for l in c["lines"]}

def height_span(line):
    z = [p[2] for p in line["samples"]]
    return max(z) - min(z)

# Penelope.
pattern, c, lines = load("penelope")
panels = {p["id"]: p for p in pattern["panels"]}
assert set(panels) == {"front", "back", "back_2"}, list(panels)
darts = {(p["id"], k["id"]): set(k["legs"]) for p in pattern["panels"] for k in p.get("darts", [])}
per_panel = {pid: sum(1 for (p, _) in darts if p == pid) for pid in panels}
assert per_panel == {"front": 4, "back": 2, "back_2": 2}, per_panel
legs = set().union(*darts.values())
seams = c["seams"]
dart_seams = [s for s in seams if s["kind"] == "dart"]
assert len(dart_seams) == 8, [s["kind"] for s in seams]
assert {frozenset((s["line_a"], s["line_b"])) for s in dart_seams} == \
    {frozenset(v) for v in darts.values()}, dart_seams
others = [s for s in seams if s["kind"] != "dart"]
assert not legs & {s[k] for s in others for k in ("line_a", "line_b")}, others
assert not legs & {l for l in lines if "unseamed" in lines[l]}
centre = [s for s in others if s["kind"] == "intra_pack"]
assert len(centre) == 1 and {lines[centre[0]["line_a"]]["panel"],
                             lines[centre[0]["line_b"]]["panel"]} == {"back", "back_2"}, centre
sides = [s for s in others if s["kind"] == "inter_half_cylinder"]
assert len(sides) == 2 and len(seams) == 11, [s["kind"] for s in seams]
for s in sides:
    a, b = lines[s["line_a"]], lines[s["line_b"]]
    assert {a["panel"], b["panel"]} in ({"front", "back"}, {"front", "back_2"}), s
    assert abs(a["length_m"] - b["length_m"]) < 0.01 * a["length_m"], (a["length_m"], b["length_m"])
    assert height_span(a) > 0.6 and height_span(b) > 0.6, s  # the full side, waist to hem
assert {lines[s["line_b"] if lines[s["line_a"]]["panel"] == "front" else s["line_a"]]["panel"]
        for s in sides} == {"back", "back_2"}, sides
print("penelope: %d darts sewn, centre back, 2 side seams (%.3f m)" %
      (len(dart_seams), lines[sides[0]["line_a"]]["length_m"]))

# Aaron.
pattern, c, lines = load("aaron")
assert {p["id"] for p in pattern["panels"]} == {"front", "back"}
assert pattern["hangs_from"] == "shoulders"
seams = c["seams"]
assert len(seams) == 4 and all(s["kind"] == "inter_half_cylinder" for s in seams), seams
chest = max(p[2] for l in lines.values() for p in l["samples"]) - 0.15
shoulders = [s for s in seams if min(lines[s["line_a"]]["centre"][2], lines[s["line_b"]]["centre"][2]) > chest]
sides = [s for s in seams if s not in shoulders]
assert len(shoulders) == 2 and len(sides) == 2, (shoulders, sides)
for s in seams:
    a, b = lines[s["line_a"]], lines[s["line_b"]]
    assert {a["panel"], b["panel"]} == {"front", "back"}, s
    assert abs(a["length_m"] - b["length_m"]) < 0.01 * a["length_m"], s
    # a shoulder and its partner on the same side of the body (x)
    assert a["centre"][0] * b["centre"][0] > 0, s
print("aaron: 2 shoulder seams (%.3f m), 2 side seams (%.3f m)" %
      (lines[shoulders[0]["line_a"]]["length_m"], lines[sides[0]["line_a"]]["length_m"]))

# Bella: the darts.
pattern, c, lines = load("bella")
per_panel = {p["id"]: len(p.get("darts", [])) for p in pattern["panels"]}
assert per_panel == {"frontSideDart": 4, "back": 1, "back_2": 1}, per_panel
darts = {frozenset(k["legs"]) for p in pattern["panels"] for k in p.get("darts", [])}
sewn = {frozenset((s["line_a"], s["line_b"])) for s in c["seams"] if s["kind"] == "dart"}
assert sewn == darts, (sewn, darts)
legs = set().union(*darts)
assert not legs & {s[k] for s in c["seams"] if s["kind"] != "dart" for k in ("line_a", "line_b")}
print("bella: %d darts sewn" % len(sewn))
PY
[ -n "$drape" ] || exit 0
runs="penelope_coarse aaron_coarse"
[ "$drape" = certified ] && runs="penelope_certified aaron_certified"
for run in $runs; do
  design=${run%_*}
  "$sartor" drape "$dir/$design.json" -options_file_yaml "$cases/$run.yaml" \
    --output "$dir/$run" --no-plot | tee "$dir/$run.log"
  "$python" - "$dir/$run" "$run" <<'PY'
import json, os, sys
s = json.load(open(os.path.join(sys.argv[1], "summary.json")))
drape = s["drape"]
outcome = drape["outcome"]
assert drape["converged"] and outcome["end"] == "on_body", outcome
assert abs(outcome["centroid_drop_m"]) < outcome["drop_tolerance_m"], outcome
assert not drape["vertex_inside_body"], drape["max_penetration_m"]
assert drape["largest_seam_gap_m"] < 1e-3, drape["largest_seam_gap_m"]
assert s["certificate"]["certified"], s["certificate"]["verdict"]
body = s["contact"]["bodies"][0]["body"]
assert "sized" in body and "mu_s=0.3" in body, body
print("%s: %d triangles, on the body, centroid drop %.3f m, lowest point %.3f m, seam gap %.1e m, "
      "certificate: %s" % (sys.argv[2], s["mesh"]["triangles"], outcome["centroid_drop_m"],
                           outcome["lowest_point_m"], drape["largest_seam_gap_m"],
                           s["certificate"]["verdict"]))
PY
done
