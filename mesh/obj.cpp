#include "mesh/obj.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "mesh/obj_lines.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

namespace sartor {

namespace {

struct Corner {
  long long vertex;  // 0-based, range not yet checked
  long long texture; // 0-based, range not yet checked
};

struct Face {
  long line;
  std::vector<Corner> corners;
  std::string group; // the last `g` statement's first name
};

class ObjParser {
public:
  ObjParser(std::string path, double uv_scale) : path_(std::move(path)), uv_scale_(uv_scale) {}

  TriangleMesh read(std::vector<std::string>* groups) {
    ObjLineReader reader(path_);
    std::string text;
    while (reader.next(text, line_)) {
      const std::vector<std::string> words = split_words(text);
      if (words.empty()) continue;
      const std::string& keyword = words[0];
      if (keyword == "v") {
        read_vertex(words);
      } else if (keyword == "vt") {
        read_texture(words);
      } else if (keyword == "f") {
        read_face(words);
      } else if (keyword == "vn") {
        ++normals_;
      } else if (keyword == "g") {
        group_ = words.size() > 1 ? words[1] : "";
      } else if (keyword == "vp" || keyword == "o" || keyword == "s" || keyword == "usemtl" ||
                 keyword == "mtllib" || keyword == "l" || keyword == "p") {
        continue;
      } else {
        fail("unknown OBJ statement '" + keyword +
             "' (a cloth mesh is read from v, vt and f lines)");
      }
    }
    if (faces_.empty()) throw InputError(path_ + ": the file has no faces (f lines)");
    TriangleMesh mesh;
    mesh.positions = std::move(positions_);
    for (const Face& face : faces_) {
      add_face(mesh, face);
      if (groups) groups->resize(mesh.triangle_count(), face.group);
    }
    validate(mesh, path_);
    return mesh;
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(path_, line_, message);
  }

  double number(const std::string& word, const char* what) const {
    const char* begin = word.data();
    const char* end = begin + word.size();
    if (end - begin > 1 && *begin == '+' && begin[1] != '-') ++begin;
    double value = 0.0;
    const auto result = std::from_chars(begin, end, value);
    if (result.ec == std::errc::result_out_of_range && result.ptr == end)
      fail(std::string(what) + ": '" + word + "' is out of double range");
    if (result.ec != std::errc() || result.ptr != end)
      fail(std::string(what) + ": '" + word + "' is not a number");
    if (!std::isfinite(value)) fail(std::string(what) + ": '" + word + "' is not a finite number");
    return value;
  }

  void read_vertex(const std::vector<std::string>& words) {
    const std::size_t count = words.size() - 1;
    if (count != 3 && count != 4 && count != 6) {
      fail("a vertex needs x y z (optionally w, or r g b), found " + std::to_string(count) +
           " values");
    }
    Eigen::Vector3d p;
    for (std::size_t k = 1; k <= count; ++k) {
      const double value = number(words[k], "vertex");
      if (k <= 3) p[static_cast<Eigen::Index>(k - 1)] = value;
    }
    positions_.push_back(p);
  }

  void read_texture(const std::vector<std::string>& words) {
    const std::size_t count = words.size() - 1;
    if (count != 2 && count != 3) {
      fail("a texture coordinate needs u and v (optionally w), found " + std::to_string(count) +
           " values");
    }
    Eigen::Vector2d uv;
    for (std::size_t k = 1; k <= count; ++k) {
      const double value = number(words[k], "texture coordinate");
      if (k <= 2) uv[static_cast<Eigen::Index>(k - 1)] = uv_scale_ * value;
    }
    if (!uv.allFinite()) fail("texture coordinate times uv_scale is not finite");
    textures_.push_back(uv);
  }

  // A 0-based index from a 1-based or negative (relative to `defined`) one;
  // positive ones are checked against the final counts in add_face.
  long long index(const std::string& word, const char* what, std::size_t defined) const {
    const char* begin = word.data();
    const char* end = begin + word.size();
    if (end - begin > 1 && *begin == '+') ++begin;
    long long value = 0;
    const auto result = std::from_chars(begin, end, value);
    if (result.ec != std::errc() || result.ptr != end || word.empty())
      fail(std::string("face corner: '") + word + "' is not a " + what + " index");
    if (value == 0) fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
    if (value > 0) return value - 1;
    const long long resolved = static_cast<long long>(defined) + value;
    if (resolved < 0) {
      fail(std::string("relative ") + what + " index " + word + " reaches before the first " +
           what + " (" + std::to_string(defined) + " defined so far)");
    }
    return resolved;
  }

  void read_face(const std::vector<std::string>& words) {
    if (words.size() < 4) {
      fail("a face needs at least 3 corners, found " + std::to_string(words.size() - 1));
    }
    Face face{line_, {}, group_};
    for (std::size_t k = 1; k < words.size(); ++k) {
      const std::string& word = words[k];
      std::vector<std::string> parts;
      std::size_t start = 0;
      while (true) {
        const auto slash = word.find('/', start);
        parts.push_back(word.substr(start, slash == std::string::npos ? slash : slash - start));
        if (slash == std::string::npos) break;
        start = slash + 1;
      }
      if (parts.size() > 3) fail("face corner '" + word + "' has more than three indices");
      const long long vertex = index(parts[0], "vertex", positions_.size());
      if (parts.size() < 2 || parts[1].empty()) {
        fail("face corner '" + word +
             "' has no texture coordinates; cloth meshes need vt for the rest shape");
      }
      const long long texture = index(parts[1], "texture coordinate", textures_.size());
      if (parts.size() == 3 && !parts[2].empty()) (void)index(parts[2], "normal", normals_);
      face.corners.push_back({vertex, texture});
    }
    faces_.push_back(std::move(face));
  }

  void add_face(TriangleMesh& mesh, const Face& face) {
    line_ = face.line;
    const auto vertices = static_cast<long long>(mesh.positions.size());
    const auto textures = static_cast<long long>(textures_.size());
    for (const Corner& corner : face.corners) {
      if (corner.vertex >= vertices) {
        fail("vertex index " + std::to_string(corner.vertex + 1) +
             " is out of range (the file has " + std::to_string(vertices) + " vertices)");
      }
      if (corner.texture >= textures) {
        fail("texture coordinate index " + std::to_string(corner.texture + 1) +
             " is out of range (the file has " + std::to_string(textures) +
             " texture coordinates)");
      }
    }
    const std::size_t n = face.corners.size();
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = a + 1; b < n; ++b) {
        if (face.corners[a].vertex == face.corners[b].vertex) {
          fail("degenerate face: vertex " + std::to_string(face.corners[a].vertex + 1) +
               " appears twice");
        }
      }
    }
    const auto uv = [&](std::size_t k) {
      return textures_[static_cast<std::size_t>(face.corners[k].texture)];
    };
    int sign = 0;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const Eigen::Vector2d d1 = uv(k) - uv(0);
      const Eigen::Vector2d d2 = uv(k + 1) - uv(0);
      const double det = d1.x() * d2.y() - d1.y() * d2.x();
      const double size2 =
          std::max({d1.squaredNorm(), d2.squaredNorm(), (uv(k + 1) - uv(k)).squaredNorm()});
      if (!(std::abs(det) > 1e-14 * size2)) {
        fail(n == 3 ? std::string("degenerate face: its texture coordinates are collinear (no "
                                  "material area)")
                    : "degenerate face: corners 1, " + std::to_string(k + 1) + ", " +
                          std::to_string(k + 2) +
                          " have collinear texture coordinates (no material area)");
      }
      const int this_sign = det > 0.0 ? 1 : -1;
      if (sign != 0 && this_sign != sign) {
        fail("the polygon's fan from its first corner folds over in (u, v) (the polygon is "
             "not convex); triangulate it before export");
      }
      sign = this_sign;
      mesh.triangles.push_back({static_cast<int>(face.corners[0].vertex),
                                static_cast<int>(face.corners[k].vertex),
                                static_cast<int>(face.corners[k + 1].vertex)});
      mesh.material_uv.push_back({uv(0), uv(k), uv(k + 1)});
    }
  }

  std::string path_;
  double uv_scale_;
  long line_ = 0;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector2d> textures_;
  std::size_t normals_ = 0; // only counted: normal indices are checked for form, then ignored
  std::vector<Face> faces_;
  std::string group_;
};

} // namespace

TriangleMesh read_obj(const std::string& path, const ObjReadOptions& options,
                      std::vector<std::string>* groups) {
  if (!(std::isfinite(options.uv_scale) && options.uv_scale > 0.0)) {
    throw InputError(path + ": uv_scale must be a positive finite number, got " +
                     format_number(options.uv_scale));
  }
  if (groups) groups->clear();
  return ObjParser(path, options.uv_scale).read(groups);
}

namespace {

// The uv of every vertex when all its triangle corners agree on one (to the
// bit); empty when some vertex has several (a seam in uv, a cut tube).
std::vector<Eigen::Vector2d> uv_per_vertex(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector2d> uv(mesh.vertex_count());
  std::vector<bool> seen(mesh.vertex_count(), false);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const auto v = std::size_t(mesh.triangles[t][c]);
      const Eigen::Vector2d& corner = mesh.material_uv[t][c];
      if (seen[v] && (uv[v].x() != corner.x() || uv[v].y() != corner.y())) return {};
      uv[v] = corner;
      seen[v] = true;
    }
  }
  return uv;
}

// vt lines and each corner's vt number: one vt per vertex, in vertex order,
// where every vertex has one uv (so that readers pairing v and vt by line,
// as meshio does, get them right); else each distinct uv once.
std::string texture_lines(const TriangleMesh& mesh,
                          std::vector<std::array<std::size_t, 3>>& corner_texture) {
  std::string out;
  corner_texture.assign(mesh.triangle_count(), {});
  const std::vector<Eigen::Vector2d> per_vertex = uv_per_vertex(mesh);
  if (!per_vertex.empty()) {
    for (const Eigen::Vector2d& uv : per_vertex)
      out += "vt " + format_number(uv.x()) + " " + format_number(uv.y()) + "\n";
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
      for (std::size_t c = 0; c < 3; ++c)
        corner_texture[t][c] = std::size_t(mesh.triangles[t][c]) + 1;
    return out;
  }
  // Distinct uv by bit pattern, so that every value reads back identically.
  const auto bits = [](double value) {
    std::uint64_t b = 0;
    std::memcpy(&b, &value, sizeof b);
    return b;
  };
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::size_t> texture_index;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const Eigen::Vector2d& uv = mesh.material_uv[t][c];
      const auto [it, inserted] =
          texture_index.try_emplace({bits(uv.x()), bits(uv.y())}, texture_index.size() + 1);
      if (inserted) out += "vt " + format_number(uv.x()) + " " + format_number(uv.y()) + "\n";
      corner_texture[t][c] = it->second;
    }
  }
  return out;
}

} // namespace

void write_obj(const std::string& path, const TriangleMesh& mesh,
               const std::vector<std::string>& groups, const std::string& comment) {
  validate(mesh, path);
  if (!groups.empty() && groups.size() != mesh.triangle_count()) {
    throw std::logic_error("write_obj: " + path + ": groups do not match the triangles");
  }
  std::string out =
      "# " +
      (comment.empty() ? "Sartor cloth mesh: " + std::to_string(mesh.vertex_count()) +
                             " vertices, " + std::to_string(mesh.triangle_count()) + " triangles"
                       : comment) +
      "; vt = material (u, v) in metres\n";
  for (const auto& p : mesh.positions) {
    out += "v " + format_number(p.x()) + " " + format_number(p.y()) + " " + format_number(p.z()) +
           "\n";
  }
  std::vector<std::array<std::size_t, 3>> corner_texture;
  out += texture_lines(mesh, corner_texture);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!groups.empty() && (t == 0 || groups[t] != groups[t - 1])) {
      out += "g " + groups[t] + "\nusemtl " + groups[t] + "\n";
    }
    out += "f";
    for (std::size_t c = 0; c < 3; ++c) {
      out += " " + std::to_string(mesh.triangles[t][c] + 1) + "/" +
             std::to_string(corner_texture[t][c]);
    }
    out += "\n";
  }
  write_file_atomically(path, out);
}

} // namespace sartor
