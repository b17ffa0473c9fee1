"""Imports sartor's OBJ files into Blender (Debian's blender, its own OBJ
importer) and checks what a user gets: one mesh with every vertex and
triangle of the file at its coordinates (z up, metres), the material (u, v)
as a UV map, one material per panel (`usemtl`) and one vertex group per
panel (`g`). Runs inside Blender:

  blender -b --factory-startup --python check_blender.py -- FILE.obj [...]

Exits 1 with the failures listed (Blender's --python-exit-code).
"""
import sys

import bpy

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def read_obj(path):
    """What the file holds, read here line by line."""
    vertices, uvs, faces, groups, materials = [], [], [], [], set()
    with open(path) as f:
        for line in f:
            word, *rest = line.split()
            if word == "v":
                vertices.append(tuple(float(c) for c in rest[:3]))
            elif word == "vt":
                uvs.append(tuple(float(c) for c in rest[:2]))
            elif word == "f":
                faces.append([tuple(int(i) - 1 for i in corner.split("/")[:2]) for corner in rest])
            elif word == "g":
                groups.append(rest[0])
            elif word == "usemtl":
                materials.add(rest[0])
    return vertices, uvs, faces, groups, materials


def check_file(path):
    vertices, uvs, faces, groups, materials = read_obj(path)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z",
                          import_vertex_groups=True, validate_meshes=True)
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    check(len(meshes) == 1, f"{path}: {len(meshes)} mesh objects")
    if not meshes:
        return
    mesh = meshes[0].data
    check(len(mesh.vertices) == len(vertices), f"{path}: {len(mesh.vertices)} of {len(vertices)} vertices")
    check(len(mesh.polygons) == len(faces), f"{path}: {len(mesh.polygons)} of {len(faces)} triangles")
    if len(mesh.vertices) == len(vertices):
        gap = max(max(abs(a - b) for a, b in zip(v.co, w)) for v, w in zip(mesh.vertices, vertices))
        check(gap < 1e-6, f"{path}: vertices moved by {gap} m on import")
    names = {m.name for m in mesh.materials}
    check(names == materials, f"{path}: materials {sorted(names)}, expected {sorted(materials)}")
    found = {g.name for g in meshes[0].vertex_groups}
    check(found == set(groups), f"{path}: vertex groups {sorted(found)}, expected {sorted(groups)}")
    if uvs:
        check(len(mesh.uv_layers) == 1, f"{path}: {len(mesh.uv_layers)} UV maps")
        layer = mesh.uv_layers[0].data
        worst = 0.0
        for polygon, face in zip(mesh.polygons, faces):
            for loop, (_, t) in zip(polygon.loop_indices, face):
                worst = max(worst, *(abs(a - b) for a, b in zip(layer[loop].uv, uvs[t])))
        check(worst < 1e-6, f"{path}: UVs differ from the file's vt by {worst}")


for path in sys.argv[sys.argv.index("--") + 1:]:
    check_file(path)
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("check_blender: every OBJ imported into Blender", bpy.app.version_string)
