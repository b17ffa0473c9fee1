#include "contact/body_obj.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/self_intersections.hpp"
#include "mesh/obj_lines.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace sartor {

namespace {

// Where a face came from, for messages ("FILE:LINE" or "CONTEXT: face N"),
// and how vertices are numbered there (1 in OBJ files, 0 in memory).
struct FaceLocator {
  std::function<std::string(std::size_t face)> place;
  int base;
  std::string operator()(std::size_t face) const { return place(face) + ": "; }
  std::string vertex(int index) const { return std::to_string(index + base); }
  std::string vertices(const std::array<int, 3>& face) const {
    return "(vertices " + vertex(face[0]) + " " + vertex(face[1]) + " " + vertex(face[2]) + ")";
  }
};

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

std::uint64_t directed_key(int from, int to) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
         static_cast<std::uint32_t>(to);
}

class DisjointSets {
public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i)
      i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

private:
  std::vector<std::size_t> parent_;
};

// Faces joined across their shared edges; the label of each face's piece.
std::vector<std::size_t> component_labels(const BodyMesh& mesh) {
  DisjointSets sets(mesh.faces.size());
  std::unordered_map<std::uint64_t, std::size_t> first_face;
  first_face.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const auto [it, inserted] =
          first_face.try_emplace(edge_key(mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]), f);
      if (!inserted) sets.join(f, it->second);
    }
  }
  std::vector<std::size_t> labels(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    labels[f] = sets.find(f);
  return labels;
}

double signed_volume_term(const BodyMesh& mesh, const std::array<int, 3>& face) {
  const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[0])];
  const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[1])];
  const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(face[2])];
  return a.dot(b.cross(c)) / 6.0;
}

void check_faces(const BodyMesh& mesh, const FaceLocator& where) {
  const auto vertex_count = static_cast<long long>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    for (int c = 0; c < 3; ++c) {
      if (face[c] < 0 || face[c] >= vertex_count) {
        throw InputError(where(f) + "vertex index " + where.vertex(face[c]) +
                         " is out of range (the mesh has " + std::to_string(vertex_count) +
                         " vertices)");
      }
    }
    if (face[0] == face[1] || face[1] == face[2] || face[2] == face[0]) {
      throw InputError(where(f) + "degenerate face " + where.vertices(face) + ": a vertex repeats");
    }
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(face[2])];
    for (const Eigen::Vector3d* p : {&a, &b, &c}) {
      if (!p->allFinite()) {
        throw InputError(where(f) + "face " + where.vertices(face) +
                         " uses a vertex with a coordinate that is not a finite number");
      }
    }
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double twice_area = (b - a).cross(c - a).norm();
    if (!(twice_area > 1e-12 * longest)) {
      throw InputError(where(f) + "degenerate face " + where.vertices(face) +
                       ": its corners are collinear or coincide (no area)");
    }
  }
}

// Edge-manifold, closed and consistently oriented, in that order of checks.
void check_edges(const BodyMesh& mesh, const FaceLocator& where) {
  struct Side {
    std::uint64_t key;
    std::size_t face;
    int from;
    int to;
  };
  std::vector<Side> sides;
  sides.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int from = mesh.faces[f][c];
      const int to = mesh.faces[f][(c + 1) % 3];
      sides.push_back({edge_key(from, to), f, from, to});
    }
  }
  std::stable_sort(sides.begin(), sides.end(),
                   [](const Side& x, const Side& y) { return x.key < y.key; });
  const auto edge_name = [&where](const Side& side) {
    return "edge (" + where.vertex(std::min(side.from, side.to)) + ", " +
           where.vertex(std::max(side.from, side.to)) + ")";
  };
  std::size_t open_edges = 0;
  const Side* first_open = nullptr;
  const Side* first_misoriented[2] = {nullptr, nullptr};
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t end = i + 1;
    while (end < sides.size() && sides[end].key == sides[i].key)
      ++end;
    if (end - i > 2) {
      std::string others;
      for (std::size_t k = i + 1; k < end; ++k)
        others += (k > i + 1 ? "; " : "") + where.place(sides[k].face);
      throw InputError(where(sides[i].face) + "non-manifold " + edge_name(sides[i]) +
                       ": shared by " + std::to_string(end - i) +
                       " faces (a body edge must have exactly two); the others: " + others);
    }
    if (end - i == 1) {
      ++open_edges;
      if (!first_open) first_open = &sides[i];
    } else if (sides[i].from == sides[i + 1].from && !first_misoriented[0]) {
      first_misoriented[0] = &sides[i];
      first_misoriented[1] = &sides[i + 1];
    }
    i = end;
  }
  if (first_open) {
    throw InputError(where(first_open->face) + "the mesh is not closed: " + edge_name(*first_open) +
                     " of face " + where.vertices(mesh.faces[first_open->face]) +
                     " has no neighbouring face (" + std::to_string(open_edges) +
                     " open edges in all); a body must be a closed surface");
  }
  if (first_misoriented[0]) {
    throw InputError(
        where(first_misoriented[0]->face) + "inconsistent orientation: this face and the face at " +
        where.place(first_misoriented[1]->face) + " run " + edge_name(*first_misoriented[0]) +
        " in the same direction; every face must be wound counter-clockwise "
        "seen from outside");
  }
}

// Around every vertex the faces must form one fan (two cones touching at a
// tip do not). With closed, consistent edges, the fan is a cycle of faces
// linked by the vertex's edges; walk it and compare with the face count.
void check_vertex_fans(const BodyMesh& mesh, const FaceLocator& where) {
  std::unordered_map<std::uint64_t, std::size_t> face_of_side;
  face_of_side.reserve(3 * mesh.faces.size());
  std::vector<std::size_t> incident(mesh.vertices.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      face_of_side[directed_key(mesh.faces[f][c], mesh.faces[f][(c + 1) % 3])] = f;
      ++incident[static_cast<std::size_t>(mesh.faces[f][c])];
    }
  }
  std::vector<bool> visited(mesh.vertices.size(), false);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int vertex = mesh.faces[f][c];
      if (visited[static_cast<std::size_t>(vertex)]) continue;
      visited[static_cast<std::size_t>(vertex)] = true;
      // Face (vertex, a, b): the next face around the vertex has side vertex -> b.
      std::size_t fan = 0;
      std::size_t current = f;
      do {
        const auto& face = mesh.faces[current];
        const int corner = face[0] == vertex ? 0 : face[1] == vertex ? 1 : 2;
        current = face_of_side.at(directed_key(vertex, face[(corner + 2) % 3]));
        ++fan;
      } while (current != f && fan <= incident[static_cast<std::size_t>(vertex)]);
      if (fan != incident[static_cast<std::size_t>(vertex)]) {
        throw InputError(where(f) + "non-manifold vertex " + where.vertex(vertex) + ": its " +
                         std::to_string(incident[static_cast<std::size_t>(vertex)]) +
                         " faces form more than one fan (surfaces touch at a point)");
      }
    }
  }
}

void check_outward(const BodyMesh& mesh, const FaceLocator& where) {
  const std::vector<std::size_t> labels = component_labels(mesh);
  std::unordered_map<std::size_t, double> volume;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    volume[labels[f]] += signed_volume_term(mesh, mesh.faces[f]);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const double v = volume[labels[f]];
    if (!(v > 0.0)) {
      throw InputError(where(f) + "the closed surface this face belongs to encloses a " +
                       (v < 0.0 ? "negative volume (" + format_number(v) +
                                      " m^3): its faces are wound inward; reverse the order "
                                      "of every face's vertices"
                                : std::string("zero volume")));
    }
  }
}

void check_embedded(const BodyMesh& mesh, const FaceLocator& where) {
  const auto crossing = self_intersecting_faces(mesh);
  if (crossing.empty()) return;
  const auto [first, second] = crossing.front();
  const std::size_t others = crossing.size() - 1;
  throw InputError(where(second) + "the surface intersects itself: this face crosses another (" +
                   where.place(first) + ")" +
                   (others > 0 ? "; " + std::to_string(others) + " more pair(s) of faces cross"
                               : std::string()) +
                   "; a body must be the boundary of a solid");
}

void check(const BodyMesh& mesh, const FaceLocator& where, const std::string& empty_context) {
  if (mesh.faces.empty()) {
    throw InputError(empty_context + "the body has no faces; a body needs a closed triangle mesh");
  }
  check_faces(mesh, where);
  check_edges(mesh, where);
  check_vertex_fans(mesh, where);
  check_outward(mesh, where);
  check_embedded(mesh, where);
}

class BodyObjParser {
public:
  explicit BodyObjParser(std::string path) : path_(std::move(path)) {}

  BodyMesh read() {
    ObjLineReader reader(path_);
    std::string logical;
    while (reader.next(logical, line_))
      statement(split_words(logical));
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
      for (int& index : mesh_.faces[f]) {
        if (index < 0) index += static_cast<int>(vertices_at_face_[f]);
      }
    }
    const FaceLocator where{
        [this](std::size_t f) { return path_ + ":" + std::to_string(face_lines_[f]); }, 1};
    check(mesh_, where, path_ + ": ");
    return std::move(mesh_);
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(path_, line_, message);
  }

  void statement(const std::vector<std::string>& words) {
    if (words.empty()) return;
    const std::string& keyword = words[0];
    if (keyword == "v") {
      read_vertex(words);
    } else if (keyword == "f") {
      read_face(words);
    } else if (keyword != "vt" && keyword != "vn" && keyword != "vp" && keyword != "o" &&
               keyword != "g" && keyword != "s" && keyword != "usemtl" && keyword != "mtllib" &&
               keyword != "l" && keyword != "p") {
      fail("unknown OBJ statement '" + keyword + "' (a body is read from v and f lines)");
    }
  }

  void read_vertex(const std::vector<std::string>& words) {
    const std::size_t count = words.size() - 1;
    if (count != 3 && count != 4 && count != 6) {
      fail("a vertex needs x y z (optionally w, or r g b), found " + std::to_string(count) +
           " values");
    }
    Eigen::Vector3d p;
    for (Eigen::Index k = 0; k < 3; ++k) {
      const std::string& word = words[static_cast<std::size_t>(k) + 1];
      const char* begin = word.data();
      const char* end = begin + word.size();
      if (end - begin > 1 && *begin == '+' && begin[1] != '-') ++begin;
      const auto result = std::from_chars(begin, end, p[k]);
      if (result.ptr != end ||
          (result.ec != std::errc() && result.ec != std::errc::result_out_of_range)) {
        fail("vertex coordinate '" + word + "' is not a number");
      }
      if (result.ec != std::errc() || !std::isfinite(p[k]))
        fail("vertex coordinate '" + word + "' is not a finite number");
    }
    mesh_.vertices.push_back(p);
  }

  // 0-based when positive (range checked later); negative (relative) ones
  // are resolved against the vertices read so far and kept negative until then.
  int vertex_index(const std::string& corner) const {
    const std::string word = corner.substr(0, corner.find('/'));
    long long value = 0;
    const char* begin = word.data();
    const char* end = begin + word.size();
    if (end - begin > 1 && *begin == '+') ++begin;
    const auto result = std::from_chars(begin, end, value);
    if (word.empty() || result.ec != std::errc() || result.ptr != end)
      fail("face corner '" + corner + "' does not start with a vertex index");
    if (value == 0) fail("vertex index 0 is invalid (OBJ indices start at 1)");
    const auto defined = static_cast<long long>(mesh_.vertices.size());
    if (value < 0 && defined + value < 0) {
      fail("relative vertex index " + word + " reaches before the first vertex (" +
           std::to_string(defined) + " defined so far)");
    }
    if (value > std::numeric_limits<int>::max()) fail("vertex index " + word + " is out of range");
    return value > 0 ? static_cast<int>(value - 1) : static_cast<int>(value);
  }

  void read_face(const std::vector<std::string>& words) {
    if (words.size() < 4)
      fail("a face needs at least 3 corners, found " + std::to_string(words.size() - 1));
    std::vector<int> corners;
    for (std::size_t k = 1; k < words.size(); ++k)
      corners.push_back(vertex_index(words[k]));
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      mesh_.faces.push_back({corners[0], corners[k], corners[k + 1]});
      face_lines_.push_back(line_);
      vertices_at_face_.push_back(mesh_.vertices.size());
    }
  }

  std::string path_;
  long line_ = 0;
  BodyMesh mesh_;
  std::vector<long> face_lines_;
  std::vector<std::size_t> vertices_at_face_; // for relative indices
};

} // namespace

BodyMesh read_body_obj(const std::string& path) {
  return BodyObjParser(path).read();
}

void check_body_mesh(const BodyMesh& mesh, const std::string& context) {
  const std::string prefix = context.empty() ? "" : context + ": ";
  const FaceLocator where{[&](std::size_t f) { return prefix + "face " + std::to_string(f); }, 0};
  check(mesh, where, prefix);
}

BodyMeasures measure_body(const BodyMesh& mesh) {
  BodyMeasures m;
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const auto& face : mesh.faces)
    for (int v : face)
      used[static_cast<std::size_t>(v)] = true;
  m.lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  m.upper = -m.lower;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!used[v]) continue;
    ++m.used_vertices;
    m.lower = m.lower.cwiseMin(mesh.vertices[v]);
    m.upper = m.upper.cwiseMax(mesh.vertices[v]);
  }
  m.shortest_edge = std::numeric_limits<double>::infinity();
  m.smallest_angle_deg = 180.0;
  for (const auto& face : mesh.faces) {
    std::array<Eigen::Vector3d, 3> p;
    for (int c = 0; c < 3; ++c)
      p[c] = mesh.vertices[static_cast<std::size_t>(face[c])];
    m.area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    m.volume += signed_volume_term(mesh, face);
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d along = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d back = p[(c + 2) % 3] - p[c];
      m.shortest_edge = std::min(m.shortest_edge, along.norm());
      m.longest_edge = std::max(m.longest_edge, along.norm());
      const double angle = std::atan2(along.cross(back).norm(), along.dot(back));
      m.smallest_angle_deg = std::min(m.smallest_angle_deg, angle * 180.0 / M_PI);
    }
  }
  m.edges = 3 * mesh.faces.size() / 2;
  const std::vector<std::size_t> labels = component_labels(mesh);
  std::vector<std::size_t> distinct(labels);
  std::sort(distinct.begin(), distinct.end());
  m.components =
      static_cast<std::size_t>(std::unique(distinct.begin(), distinct.end()) - distinct.begin());
  m.euler_characteristic = static_cast<long>(m.used_vertices) - static_cast<long>(m.edges) +
                           static_cast<long>(mesh.faces.size());
  return m;
}

void write_body_obj(const std::string& path, const BodyMesh& mesh,
                    const std::vector<std::string>& comment) {
  std::string out;
  for (const std::string& line : comment)
    out += "# " + line + "\n";
  for (const auto& p : mesh.vertices) {
    out += "v " + format_number(p.x()) + " " + format_number(p.y()) + " " + format_number(p.z()) +
           "\n";
  }
  for (const auto& face : mesh.faces) {
    out += "f " + std::to_string(face[0] + 1) + " " + std::to_string(face[1] + 1) + " " +
           std::to_string(face[2] + 1) + "\n";
  }
  write_file_atomically(path, out);
}

} // namespace sartor
