#include "mesh/seams.hpp"

#include "common/autodiff.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/json_input.hpp"
#include "common/output.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <type_traits>

namespace sartor {

namespace {

constexpr double match_tolerance = 1e-6; // on normalised arc length

std::string seam_label(const std::vector<Seam>& seams, std::size_t index) {
  return "seam " + std::to_string(index) + " ('" + seams[index].name + "')";
}

// The triangles on each undirected edge (lo, hi), for boundary checks and the
// material length of seam segments.
using EdgeTriangles = std::map<std::pair<int, int>, std::vector<int>>;

EdgeTriangles edge_triangles(const TriangleMesh& mesh) {
  EdgeTriangles edges;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const int p = mesh.triangles[t][c];
      const int q = mesh.triangles[t][(c + 1) % 3];
      edges[{std::min(p, q), std::max(p, q)}].push_back(int(t));
    }
  }
  return edges;
}

// The springs are built on double for their values and on AutoDiff for
// their change with the material coordinates (seam_spring_changes): the
// same source, the lengths of the seams' segments seeded with their changes.

// Material length of the edge p-q in triangle t; as an AutoDiff, with its
// change when the triangle's corners move by (*change)[t].
template <class Scalar>
Scalar segment_length(const TriangleMesh& mesh, const MaterialChange* change, int t, int p, int q) {
  const auto& tri = mesh.triangles[std::size_t(t)];
  const auto& uv = mesh.material_uv[std::size_t(t)];
  std::size_t cp = 0, cq = 0;
  Eigen::Vector2d up = Eigen::Vector2d::Zero(), uq = Eigen::Vector2d::Zero();
  for (std::size_t c = 0; c < 3; ++c) {
    if (tri[c] == p) up = uv[cp = c];
    if (tri[c] == q) uq = uv[cq = c];
  }
  const double length = (uq - up).norm();
  if constexpr (std::is_same_v<Scalar, double>) {
    return length;
  } else {
    const auto& delta = (*change)[std::size_t(t)];
    return seeded(length, (uq - up).dot(delta[cq] - delta[cp]) / length);
  }
}

template <class Scalar>
std::vector<Scalar> arc_length(const TriangleMesh& mesh, const EdgeTriangles& edges,
                               const std::vector<int>& line,
                               const MaterialChange* change = nullptr) {
  std::vector<Scalar> length(line.size(), Scalar(0.0));
  for (std::size_t i = 1; i < line.size(); ++i) {
    const int p = line[i - 1], q = line[i];
    const auto found = edges.find({std::min(p, q), std::max(p, q)});
    if (found == edges.end()) {
      throw InputError("vertices " + std::to_string(p) + " and " + std::to_string(q) +
                       " are not joined by a mesh edge");
    }
    length[i] = length[i - 1] + segment_length<Scalar>(mesh, change, found->second.front(), p, q);
  }
  return length;
}

template <class Scalar>
std::vector<Scalar> normalised(std::vector<Scalar> length) {
  const Scalar total = length.back();
  for (Scalar& t : length)
    t = t / total;
  return length;
}

// Half the material length of the segments next to each vertex, m.
template <class Scalar>
std::vector<Scalar> tributary_length(const std::vector<Scalar>& arc) {
  std::vector<Scalar> tributary(arc.size(), Scalar(0.0));
  for (std::size_t i = 1; i < arc.size(); ++i) {
    const Scalar half = 0.5 * (arc[i] - arc[i - 1]);
    tributary[i - 1] += half;
    tributary[i] += half;
  }
  return tributary;
}

std::vector<int> paired_b(const Seam& seam) {
  std::vector<int> b = seam.b;
  if (seam.reverse) std::reverse(b.begin(), b.end());
  return b;
}

template <class Scalar>
bool lines_match(const std::vector<Scalar>& ta, const std::vector<Scalar>& tb) {
  if (ta.size() != tb.size()) return false;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    if (std::abs(value_of(ta[i]) - value_of(tb[i])) > match_tolerance) return false;
  }
  return true;
}

// A spring with its stiffness and edge parameter in either scalar.
template <class Scalar>
struct BuiltSpring {
  SeamSpring spring;
  Scalar stiffness, s;
};

// Springs from every vertex of `emitting` to the point of `receiving` at the
// same normalised arc length: vertex-to-edge, or vertex-to-vertex where the
// point is (within the match tolerance) a vertex.
template <class Scalar>
void emit_to_edges(const std::vector<int>& emitting, const std::vector<Scalar>& t_emitting,
                   const std::vector<Scalar>& tributary, const std::vector<int>& receiving,
                   const std::vector<Scalar>& t_receiving, Scalar kappa, int seam,
                   std::vector<BuiltSpring<Scalar>>& springs) {
  for (std::size_t i = 0; i < emitting.size(); ++i) {
    const Scalar t = t_emitting[i];
    // The receiving segment [j, j + 1] holding t.
    const auto upper = std::upper_bound(t_receiving.begin(), t_receiving.end(), t);
    std::size_t j = std::size_t(std::max<long>(0, long(upper - t_receiving.begin()) - 1));
    j = std::min(j, t_receiving.size() - 2);
    const Scalar s =
        std::clamp(Scalar((t - t_receiving[j]) / (t_receiving[j + 1] - t_receiving[j])),
                   Scalar(0.0), Scalar(1.0));
    BuiltSpring<Scalar> built{SeamSpring{}, Scalar(0.0), Scalar(0.0)};
    SeamSpring& spring = built.spring;
    spring.seam = seam;
    const Scalar length = 0.5 * tributary[i]; // both lines emit: half each
    built.stiffness = kappa * length;
    spring.length = value_of(length);
    spring.vertices[0] = emitting[i];
    const double gap = value_of(t_receiving[j + 1] - t_receiving[j]);
    if (value_of(s) * gap <= match_tolerance) {
      spring.vertices[1] = receiving[j];
    } else if ((1.0 - value_of(s)) * gap <= match_tolerance) {
      spring.vertices[1] = receiving[j + 1];
    } else {
      spring.to_edge = true;
      built.s = s;
      spring.vertices[1] = receiving[j];
      spring.vertices[2] = receiving[j + 1];
    }
    if (!spring.to_edge && spring.vertices[0] == spring.vertices[1]) continue; // a dart's tip
    springs.push_back(built);
  }
}

std::vector<int> vertex_list(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array()) throw InputError(where + " must be an array of vertex indices");
  std::vector<int> vertices;
  for (const auto& item : value) {
    if (!item.is_number_integer()) {
      throw InputError(where + ": " +
                       item.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                       " is not a vertex index (an integer)");
    }
    vertices.push_back(item.get<int>());
  }
  return vertices;
}

} // namespace

void check_seams(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                 const std::string& context) {
  const EdgeTriangles edges = edge_triangles(mesh);
  const std::string prefix = context.empty() ? "" : context + ": ";
  for (std::size_t index = 0; index < seams.size(); ++index) {
    const Seam& seam = seams[index];
    const std::string label = prefix + seam_label(seams, index);
    if (!(seam.certainty > 0.0 && seam.certainty <= 1.0)) {
      throw InputError(label + ": certainty must lie in (0, 1], got " +
                       format_number(seam.certainty));
    }
    for (const auto& [side, line] : {std::pair{"a", &seam.a}, std::pair{"b", &seam.b}}) {
      const std::size_t triangles_on_edge = seam.t_seam && line == &seam.b ? 2 : 1;
      const std::string where = label + ": line " + side;
      if (line->size() < 2) {
        throw InputError(where + " has " + std::to_string(line->size()) +
                         " vertex(es); a seam line needs at least 2");
      }
      std::set<int> seen;
      for (int v : *line) {
        if (v < 0 || std::size_t(v) >= mesh.vertex_count()) {
          throw InputError(where + ": vertex " + std::to_string(v) + " is not in the mesh (0.." +
                           std::to_string(mesh.vertex_count() - 1) + ")");
        }
        if (!seen.insert(v).second) {
          throw InputError(where + ": vertex " + std::to_string(v) + " appears twice");
        }
      }
      for (std::size_t i = 1; i < line->size(); ++i) {
        const int p = (*line)[i - 1], q = (*line)[i];
        const auto found = edges.find({std::min(p, q), std::max(p, q)});
        if (found == edges.end()) {
          throw InputError(where + ": vertices " + std::to_string(p) + " and " + std::to_string(q) +
                           " are not joined by a mesh edge");
        }
        if (found->second.size() != triangles_on_edge) {
          throw InputError(where + ": edge " + std::to_string(p) + "-" + std::to_string(q) +
                           (triangles_on_edge == 1 ? " is not on a panel boundary"
                                                   : " of a T-seam is not inside a panel") +
                           " (it has " + std::to_string(found->second.size()) + " triangles)");
        }
      }
    }
  }
}

std::vector<Seam> read_seams(const std::string& path, const TriangleMesh& mesh) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the seam file");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  nlohmann::json document = parse_json_input(text, path);
  if (!document.is_object() || !document.contains("seams") || !document["seams"].is_array()) {
    throw InputError(path + ": expected an object {\"seams\": [...]}");
  }
  // A seam joins two boundary lines: more seams than boundary edges cannot be.
  const std::size_t most_seams = std::max<std::size_t>(1, mesh.triangle_count());
  if (document["seams"].size() > most_seams) {
    throw InputError(path + ": " + std::to_string(document["seams"].size()) +
                     " seams, more than the mesh's " + std::to_string(most_seams) +
                     " triangles could have");
  }
  std::vector<Seam> seams;
  for (const auto& entry : document["seams"]) {
    const std::string where = path + ": seam " + std::to_string(seams.size());
    if (!entry.is_object()) throw InputError(where + ": expected an object");
    Seam seam;
    seam.name = "seam " + std::to_string(seams.size());
    for (const auto& [key, value] : entry.items()) {
      if (key == "name") {
        if (!value.is_string()) throw InputError(where + ": 'name' must be a string");
        seam.name = value.get<std::string>();
      } else if (key == "a" || key == "b") {
        (key == "a" ? seam.a : seam.b) = vertex_list(value, where + ": '" + key + "'");
      } else if (key == "reverse") {
        if (!value.is_boolean()) throw InputError(where + ": 'reverse' must be true or false");
        seam.reverse = value.get<bool>();
      } else if (key == "certainty") {
        if (!value.is_number()) throw InputError(where + ": 'certainty' must be a number");
        seam.certainty = value.get<double>();
      } else if (key == "t_seam") {
        if (!value.is_boolean()) throw InputError(where + ": 't_seam' must be true or false");
        seam.t_seam = value.get<bool>();
      } else {
        throw InputError(where + ": unknown key '" + key +
                         "' (expected name, a, b, reverse, certainty, t_seam)");
      }
    }
    if (!entry.contains("a") || !entry.contains("b")) {
      throw InputError(where + ": needs both seam lines 'a' and 'b'");
    }
    seams.push_back(std::move(seam));
  }
  check_seams(mesh, seams, path);
  return seams;
}

void write_seams(const std::string& path, const std::vector<Seam>& seams) {
  nlohmann::json list = nlohmann::json::array();
  for (const Seam& seam : seams) {
    list.push_back({{"name", seam.name},
                    {"a", seam.a},
                    {"b", seam.b},
                    {"reverse", seam.reverse},
                    {"certainty", seam.certainty}});
    if (seam.t_seam) list.back()["t_seam"] = true;
  }
  write_json(path, nlohmann::json{{"seams", list}});
}

std::vector<double> material_arc_length(const TriangleMesh& mesh, const std::vector<int>& line) {
  return arc_length<double>(mesh, edge_triangles(mesh), line);
}

bool seam_is_matched(const TriangleMesh& mesh, const Seam& seam) {
  const EdgeTriangles edges = edge_triangles(mesh);
  return lines_match(normalised(arc_length<double>(mesh, edges, seam.a)),
                     normalised(arc_length<double>(mesh, edges, paired_b(seam))));
}

namespace {

template <class Scalar>
std::vector<BuiltSpring<Scalar>>
build_springs(const TriangleMesh& mesh, const std::vector<Seam>& seams,
              const SeamStiffness& stiffness, const MaterialChange* change) {
  check_seams(mesh, seams, "");
  const EdgeTriangles edges = edge_triangles(mesh);
  std::vector<BuiltSpring<Scalar>> springs;
  for (std::size_t index = 0; index < seams.size(); ++index) {
    const Seam& seam = seams[index];
    const std::vector<int> b = paired_b(seam);
    const std::vector<Scalar> arc_a = arc_length<Scalar>(mesh, edges, seam.a, change);
    const std::vector<Scalar> arc_b = arc_length<Scalar>(mesh, edges, b, change);
    const Scalar spacing =
        (arc_a.back() + arc_b.back()) / double(seam.a.size() + seam.b.size() - 2);
    const Scalar kappa =
        seam.certainty * (stiffness.per_length > 0.0
                              ? Scalar(stiffness.per_length)
                              : Scalar(stiffness.penalty * stiffness.modulus / spacing));
    const std::vector<Scalar> ta = normalised(arc_a), tb = normalised(arc_b);
    const std::vector<Scalar> tributary_a = tributary_length(arc_a);
    const std::vector<Scalar> tributary_b = tributary_length(arc_b);
    if (lines_match(ta, tb)) {
      for (std::size_t i = 0; i < ta.size(); ++i) {
        if (seam.a[i] == b[i]) continue; // a dart's tip
        BuiltSpring<Scalar> built{SeamSpring{}, Scalar(0.0), Scalar(0.0)};
        built.spring.seam = int(index);
        built.spring.vertices[0] = seam.a[i];
        built.spring.vertices[1] = b[i];
        const Scalar length = 0.5 * (tributary_a[i] + tributary_b[i]);
        built.spring.length = value_of(length);
        built.stiffness = kappa * length;
        springs.push_back(built);
      }
    } else {
      emit_to_edges(seam.a, ta, tributary_a, b, tb, kappa, int(index), springs);
      emit_to_edges(b, tb, tributary_b, seam.a, ta, kappa, int(index), springs);
    }
  }
  return springs;
}

} // namespace

std::vector<SeamSpring> seam_springs(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                                     const SeamStiffness& stiffness) {
  std::vector<SeamSpring> springs;
  for (const BuiltSpring<double>& built : build_springs<double>(mesh, seams, stiffness, nullptr)) {
    springs.push_back(built.spring);
    springs.back().stiffness = built.stiffness;
    springs.back().s = built.s;
  }
  return springs;
}

std::vector<SeamSpringChange> seam_spring_changes(const TriangleMesh& mesh,
                                                  const std::vector<Seam>& seams,
                                                  const SeamStiffness& stiffness,
                                                  const MaterialChange& change) {
  if (change.size() != mesh.triangle_count()) {
    throw InputError("seam springs: a material change of " + std::to_string(change.size()) +
                     " triangles for a mesh of " + std::to_string(mesh.triangle_count()));
  }
  std::vector<SeamSpringChange> changes;
  for (const BuiltSpring<AutoDiff>& built :
       build_springs<AutoDiff>(mesh, seams, stiffness, &change))
    changes.push_back({derivative_of(built.stiffness), derivative_of(built.s)});
  return changes;
}

std::vector<std::pair<int, int>> matched_vertex_pairs(const TriangleMesh& mesh,
                                                      const std::vector<Seam>& seams) {
  check_seams(mesh, seams, "");
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t index = 0; index < seams.size(); ++index) {
    if (seams[index].t_seam) {
      throw InputError(seam_label(seams, index) +
                       ": a T-seam cannot be merged (its edges would join three triangles); "
                       "sew it with springs only");
    }
    if (!seam_is_matched(mesh, seams[index])) {
      throw InputError(
          seam_label(seams, index) + ": its lines are not discretised alike (vertex counts " +
          std::to_string(seams[index].a.size()) + " and " + std::to_string(seams[index].b.size()) +
          "), so its vertices cannot be merged; sew it with springs only");
    }
    const std::vector<int> b = paired_b(seams[index]);
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (seams[index].a[i] != b[i]) pairs.emplace_back(seams[index].a[i], b[i]);
    }
  }
  return pairs;
}

double seam_spring_gap(const SeamSpring& spring, const std::vector<Eigen::Vector3d>& positions) {
  const Eigen::Vector3d& a = positions[std::size_t(spring.vertices[0])];
  const Eigen::Vector3d& b = positions[std::size_t(spring.vertices[1])];
  const Eigen::Vector3d anchor =
      spring.to_edge ? Eigen::Vector3d((1.0 - spring.s) * b +
                                       spring.s * positions[std::size_t(spring.vertices[2])])
                     : b;
  return (a - anchor).norm();
}

double largest_seam_gap(const std::vector<SeamSpring>& springs,
                        const std::vector<Eigen::Vector3d>& positions) {
  double largest = 0.0;
  for (const SeamSpring& spring : springs)
    largest = std::max(largest, seam_spring_gap(spring, positions));
  return largest;
}

} // namespace sartor
