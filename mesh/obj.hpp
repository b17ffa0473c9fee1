#pragma once
// Wavefront OBJ for cloth meshes. The rest shape comes from the texture
// coordinates: every face corner needs a vt, read as material (u, v) in
// metres (times ObjReadOptions::uv_scale); v lines give the initial 3D
// placement. Corners that share a v but not a vt keep their own uv, so a
// closed tube's seam needs no duplicated vertices.
//
// Read: `v x y z [w | r g b]`, `vt u v [w]`, `f` with corners `a/b` or
// `a/b/c` (normals ignored), 1-based or negative (relative) indices, polygons
// fan-triangulated from their first corner; `#` comments, `\` line
// continuations; `g NAME` names the faces after it (read_obj's groups);
// `vn vp o s usemtl mtllib l p` are ignored (material ids
// are not read: the mesh comes back with none). Any other statement, a bad
// number or index, a face without vt, a face that repeats a vertex, has no
// material area or whose fan folds is an InputError at FILE:LINE; the result
// passes validate().

#include "mesh/triangle_mesh.hpp"

#include <string>
#include <vector>

namespace sartor {

struct ObjReadOptions {
  double uv_scale = 1.0; // multiplies every vt: file units to metres
};

// `groups` (optional) receives per triangle the name of the `g` statement
// before its face ("" before any).
TriangleMesh read_obj(const std::string& path, const ObjReadOptions& options = {},
                      std::vector<std::string>* groups = nullptr);

// v per vertex; vt one per vertex in vertex order where every vertex has a
// single uv (then v and vt pair by line, as meshio reads them), else each
// distinct uv once; f a/b per triangle; numbers in the shortest form that
// reads back to the same double; written atomically (complete or not at
// all). `groups` (one name per triangle, or empty) starts a `g NAME` and
// `usemtl NAME` wherever the name changes; `comment` replaces the counts in
// the first line. Material ids are not written otherwise.
void write_obj(const std::string& path, const TriangleMesh& mesh,
               const std::vector<std::string>& groups = {}, const std::string& comment = "");

} // namespace sartor
