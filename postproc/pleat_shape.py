#!/usr/bin/python3
"""The folds of a draped garment: the dihedral angle at every creased fold
line of a `sartor construct` or `sartor drape` output folder, at the start
(garment.obj) and at the end (final.obj), against the crease's rest angle,
and the pleats that formed.

    postproc/pleat_shape.py DIR [--json FILE] [--series]

A crease line's angle is the mean over its mesh edges of the signed dihedral
angle of element/bending.hpp: theta = atan2((n1 x n2) . e, n1 . n2), n1 and n2
the normals of the edge's two triangles from their own winding, e the unit
edge as the first triangle runs it (> 0: a ridge seen from the side the
normals face). A crease is *formed* when its angle has the rest angle's sign
and at least half its size; a pleat (the creases of one slash line, the
generator's PLEATS_K_* lines) is formed when all its creases are. Lines
that are not pleat creases (a lapel's) are reported but not counted as
pleats. --series also follows them through the drape's fall (series.h5:
every output state), one row per state: time, pleats formed, and the mean
over creases of angle / rest angle.
"""

import argparse
import json
import math
import os
import re
import sys
from collections import defaultdict

import numpy as np


def read_obj(path):
    positions, faces = [], []
    with open(path) as obj:
        for line in obj:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                positions.append([float(w) for w in words[1:4]])
            elif words[0] == "f":
                faces.append([int(w.split("/")[0]) - 1 for w in words[1:4]])
    return np.array(positions), faces


def edge_faces(faces):
    """(a, b) with a < b -> the faces holding the edge, with the edge's
    direction in each face's winding."""
    table = defaultdict(list)
    for f, corners in enumerate(faces):
        for k in range(3):
            a, b = corners[k], corners[(k + 1) % 3]
            table[(min(a, b), max(a, b))].append((f, a, b))
    return table


def dihedral(x, faces, table, a, b):
    entries = table.get((min(a, b), max(a, b)), [])
    if len(entries) != 2:
        raise SystemExit(f"pleat_shape: edge {a}-{b} is not an interior edge of the mesh")
    (f1, s, t), (f2, _, _) = entries
    normals = []
    for f in (f1, f2):
        p = x[faces[f]]
        normals.append(np.cross(p[1] - p[0], p[2] - p[0]))
    n1, n2 = (n / np.linalg.norm(n) for n in normals)
    e = x[t] - x[s]
    e = e / np.linalg.norm(e)
    return math.atan2(np.dot(np.cross(n1, n2), e), np.dot(n1, n2))


def crease_angles(obj_path, creases, positions=None):
    x, faces = read_obj(obj_path)
    if positions is not None:
        x = positions
    table = edge_faces(faces)
    angles = {}
    for crease in creases:
        v = crease["vertices"]
        values = [dihedral(x, faces, table, v[i], v[i + 1]) for i in range(len(v) - 1)]
        angles[crease["line"]] = math.degrees(sum(values) / len(values))
    return angles


def formed(angle, rest):
    return angle * rest > 0 and abs(angle) >= 0.5 * abs(rest)


def pleat_groups(creases):
    groups = defaultdict(list)
    for crease in creases:
        match = re.match(r"(.+)_(\d+)_\d+_(out|in)$", crease["line"])
        if match:
            groups[(match.group(1), int(match.group(2)))].append(crease)
    return groups


def follow_series(directory, creases):
    import h5py
    groups = pleat_groups(creases)
    obj = os.path.join(directory, "garment.obj")
    print(f"{'time (s)':>9s} {'pleats formed':>14s} {'angle / rest':>13s}")
    rows = []
    with h5py.File(os.path.join(directory, "series.h5"), "r") as series:
        for name in sorted(series["steps"]):
            step = series["steps"][name]
            time = float(np.array(step["time"]).ravel()[0])
            angles = crease_angles(obj, creases, np.array(step["fields/position"]))
            ok = {c["line"]: formed(angles[c["line"]], c["rest_angle_deg"]) for c in creases}
            count = sum(all(ok[c["line"]] for c in g) for g in groups.values())
            ratio = np.mean([angles[c["line"]] / c["rest_angle_deg"] for c in creases])
            rows.append({"time_s": time, "pleats_formed": count, "angle_over_rest": ratio})
            print(f"{time:9.3f} {count:8d} of {len(groups):<3d} {ratio:13.3f}")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", help="output folder of sartor construct or sartor drape")
    parser.add_argument("--json", help="also write the table as JSON to FILE")
    parser.add_argument("--series", action="store_true",
                        help="also follow the creases through series.h5 (drape's output states)")
    args = parser.parse_args()
    construct = json.load(open(os.path.join(args.dir, "construct.json")))
    creases = construct.get("creases", [])
    if not creases:
        raise SystemExit(f"pleat_shape: {args.dir}/construct.json lists no creases")
    start = crease_angles(os.path.join(args.dir, "garment.obj"), creases)
    final_path = os.path.join(args.dir, "final.obj")
    final = crease_angles(final_path, creases) if os.path.exists(final_path) else None
    pleats = defaultdict(list)
    rows = []
    print(f"{'crease line':24s} {'rest':>8s} {'start':>8s} {'final':>8s}  formed")
    for crease in creases:
        line, rest = crease["line"], crease["rest_angle_deg"]
        end = final[line] if final else start[line]
        ok = formed(end, rest)
        rows.append({"line": line, "rest_deg": rest, "start_deg": start[line],
                     "final_deg": final[line] if final else None, "formed": ok})
        print(f"{line:24s} {rest:8.1f} {start[line]:8.1f} "
              f"{(final[line] if final else float('nan')):8.1f}  {'yes' if ok else 'no'}")
        match = re.match(r"(.+)_(\d+)_\d+_(out|in)$", line)
        if match:
            pleats[(match.group(1), int(match.group(2)))].append(ok)
    count = sum(all(v) for v in pleats.values())
    print(f"pleats: {count} of {len(pleats)} formed "
          f"({'final' if final else 'start'} shape)")
    history = follow_series(args.dir, creases) if args.series else None
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"creases": rows, "pleats": len(pleats), "pleats_formed": count,
                       "series": history}, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
