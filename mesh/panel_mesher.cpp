#include "mesh/panel_mesher.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace sartor {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact_predicates_tag: interior lines may cross each other; CGAL then inserts
// the crossing (computed in floating point).
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Triangulation>;
using Mesher = CGAL::Delaunay_mesher_2<Triangulation, Criteria>;
using Vertex = Triangulation::Vertex_handle;
using Point = Kernel::Point_2;
using Eigen::Vector2d;

constexpr double degrees = 180 / M_PI;

Vector2d to_eigen(const Point& p) {
  return {p.x(), p.y()};
}

// A line as inserted: its discretisation points and their vertices.
struct InsertedLine {
  std::vector<Vertex> vertices; // pieces + 1, start to end
};

// The vertices along the constrained segment a -> b after refinement: a, the
// vertices the mesher put on it in order, b.
std::vector<Vertex> walk_constraint(const Triangulation& triangulation, Vertex a, Vertex b) {
  std::vector<Vertex> path{a};
  const Vector2d pa = to_eigen(a->point()), pb = to_eigen(b->point());
  const Vector2d direction = pb - pa;
  const double length = direction.norm();
  double reached = 0;
  Vertex current = a;
  while (current != b) {
    Vertex best;
    double best_parameter = 2;
    auto edges = triangulation.incident_edges(current), end = edges;
    do {
      if (triangulation.is_infinite(edges) || !triangulation.is_constrained(*edges)) continue;
      const auto& [face, index] = *edges;
      Vertex other = face->vertex(Triangulation::cw(index));
      if (other == current) other = face->vertex(Triangulation::ccw(index));
      const Vector2d offset = to_eigen(other->point()) - pa;
      const double parameter = offset.dot(direction) / (length * length);
      const double off_line = std::abs(offset.x() * direction.y() - offset.y() * direction.x());
      if (off_line <= 1e-9 * length * length && parameter > reached + 1e-12 &&
          parameter < best_parameter) {
        best = other;
        best_parameter = parameter;
      }
    } while (++edges != end);
    if (best == Vertex()) {
      throw std::logic_error("panel mesher: lost the constrained segment from (" +
                             format_number(pa.x()) + ", " + format_number(pa.y()) + ")");
    }
    path.push_back(best);
    reached = best_parameter;
    current = best;
  }
  return path;
}

std::vector<Vertex> walk_line(const Triangulation& triangulation, const InsertedLine& line) {
  std::vector<Vertex> path{line.vertices.front()};
  for (std::size_t k = 0; k + 1 < line.vertices.size(); ++k) {
    const auto piece = walk_constraint(triangulation, line.vertices[k], line.vertices[k + 1]);
    path.insert(path.end(), piece.begin() + 1, piece.end());
  }
  return path;
}

double triangle_min_angle(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const auto angle = [](const Vector2d& p, const Vector2d& q, const Vector2d& r) {
    const Vector2d u = q - p, v = r - p;
    return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * degrees;
}

// The smallest angle between consecutive constrained edges at a vertex
// (360 degrees when fewer than two meet there).
double constraint_angle(const Triangulation& triangulation, Vertex v) {
  std::vector<double> directions;
  auto edges = triangulation.incident_edges(v), end = edges;
  do {
    if (triangulation.is_infinite(edges) || !triangulation.is_constrained(*edges)) continue;
    const auto& [face, index] = *edges;
    Vertex other = face->vertex(Triangulation::cw(index));
    if (other == v) other = face->vertex(Triangulation::ccw(index));
    const Vector2d d = to_eigen(other->point()) - to_eigen(v->point());
    directions.push_back(std::atan2(d.y(), d.x()));
  } while (++edges != end);
  if (directions.size() < 2) return 360;
  std::sort(directions.begin(), directions.end());
  double smallest = directions.front() + 2 * M_PI - directions.back();
  for (std::size_t k = 1; k < directions.size(); ++k)
    smallest = std::min(smallest, directions[k] - directions[k - 1]);
  return smallest * degrees;
}

struct Attempt {
  Triangulation triangulation;
  std::vector<InsertedLine> outline, interior;
  std::vector<std::vector<Vertex>> outline_paths; // after refinement
};

void insert_line(Triangulation& triangulation, const std::vector<Vector2d>& points,
                 InsertedLine& line) {
  for (const auto& p : points)
    line.vertices.push_back(triangulation.insert(Point(p.x(), p.y())));
  for (std::size_t k = 0; k + 1 < line.vertices.size(); ++k)
    triangulation.insert_constraint(line.vertices[k], line.vertices[k + 1]);
}

void check_mesh_options(const std::string& where, const PanelMeshOptions& options) {
  if (!(options.edge_length > 0))
    throw InputError(where + ": the edge length must be > 0, got " +
                     format_number(options.edge_length));
  if (!(options.min_angle_deg > 0 && options.min_angle_deg <= 33)) {
    throw InputError(where + ": the minimum angle must be in (0, 33] degrees (CGAL's " +
                     "refinement need not terminate above), got " +
                     format_number(options.min_angle_deg));
  }
}

// The pieces of each outline line, and whether options.pieces forces them.
struct OutlinePieces {
  std::vector<int> pieces;
  std::vector<bool> forced;
};

OutlinePieces outline_pieces(const garment::Panel& panel, const PanelMeshOptions& options,
                             const std::string& where) {
  // A polygon needs three corners: one or two outline lines get more pieces.
  const int at_least = panel.outline.size() >= 3 ? 1 : panel.outline.size() == 2 ? 2 : 3;
  OutlinePieces result;
  for (const auto& line : panel.outline) {
    const auto found = options.pieces.find(line.id);
    result.forced.push_back(found != options.pieces.end());
    if (found != options.pieces.end() && found->second < at_least) {
      throw InputError(where + ": line '" + line.id + "' is forced to " +
                       std::to_string(found->second) + " pieces; it needs at least " +
                       std::to_string(at_least));
    }
    result.pieces.push_back(
        result.forced.back()
            ? found->second
            : std::max(at_least, pieces_for(line.curve.length(), options.edge_length)));
  }
  return result;
}

// The panel's lines inserted as constraints and refined by CGAL; an outline
// line the mesher split is inserted again with twice the pieces (unless
// forced, or after options.max_rounds rounds), so that outline vertices
// stay equally spaced. `outline.pieces` ends as used; *rounds counts them.
std::unique_ptr<Attempt> refine_panel(const garment::Panel& panel, const PanelMeshOptions& options,
                                      OutlinePieces& outline, int* rounds) {
  const double sine = std::sin(options.min_angle_deg / degrees);
  std::vector<int>& pieces = outline.pieces;
  std::unique_ptr<Attempt> attempt;
  for (;;) {
    ++*rounds;
    attempt = std::make_unique<Attempt>();
    attempt->outline.resize(panel.outline.size());
    for (std::size_t l = 0; l < panel.outline.size(); ++l) {
      insert_line(attempt->triangulation, panel.outline[l].curve.split_equal_arc_length(pieces[l]),
                  attempt->outline[l]);
    }
    attempt->interior.resize(panel.interior.size());
    for (std::size_t l = 0; l < panel.interior.size(); ++l) {
      const auto& curve = panel.interior[l].curve;
      insert_line(attempt->triangulation,
                  curve.split_equal_arc_length(pieces_for(curve.length(), options.edge_length)),
                  attempt->interior[l]);
    }
    CGAL::refine_Delaunay_mesh_2(attempt->triangulation,
                                 Criteria(sine * sine, options.edge_length));

    bool again = false;
    for (std::size_t l = 0; l < panel.outline.size(); ++l) {
      attempt->outline_paths.push_back(walk_line(attempt->triangulation, attempt->outline[l]));
      const bool split =
          attempt->outline_paths.back().size() != attempt->outline[l].vertices.size();
      if (split && !outline.forced[l] && *rounds < options.max_rounds) {
        pieces[l] *= 2;
        again = true;
      }
    }
    if (!again) return attempt;
  }
}

// Mesh vertex numbers in the order vertices are first met; a vertex met
// for the first time is added to the mesh.
struct VertexNumbering {
  TriangleMesh& mesh;
  std::map<Vertex, int> index;
  int operator()(Vertex v) {
    const auto [it, inserted] = index.emplace(v, int(mesh.positions.size()));
    if (inserted) {
      const Vector2d p = to_eigen(v->point());
      mesh.positions.emplace_back(p.x(), p.y(), 0.0);
    }
    return it->second;
  }
};

// The triangles of the domain with their material coordinates, the area,
// and the smallest angles (overall, and away from input corners sharper
// than the minimum angle, which no refinement can improve).
void add_triangles(const Attempt& attempt, const garment::Panel& panel,
                   const PanelMeshOptions& options, VertexNumbering& number, PanelMesh* result) {
  result->min_angle_deg = 180;
  result->min_angle_regular_deg = 180;
  std::map<Vertex, bool> sharp_input;
  for (auto face = attempt.triangulation.finite_faces_begin();
       face != attempt.triangulation.finite_faces_end(); ++face) {
    if (!face->is_in_domain()) continue;
    std::array<int, 3> triangle{};
    std::array<Eigen::Vector2d, 3> uv;
    std::array<Vector2d, 3> xy;
    bool near_sharp_input = false;
    for (int c = 0; c < 3; ++c) {
      const Vertex v = face->vertex(c);
      triangle[c] = number(v);
      xy[c] = to_eigen(v->point());
      uv[c] = panel.grain.material_uv(xy[c]);
      auto [it, inserted] = sharp_input.emplace(v, false);
      if (inserted) it->second = constraint_angle(attempt.triangulation, v) < options.min_angle_deg;
      near_sharp_input = near_sharp_input || it->second;
    }
    const double angle = triangle_min_angle(xy[0], xy[1], xy[2]);
    result->min_angle_deg = std::min(result->min_angle_deg, angle);
    if (!near_sharp_input)
      result->min_angle_regular_deg = std::min(result->min_angle_regular_deg, angle);
    const Vector2d e1 = xy[1] - xy[0], e2 = xy[2] - xy[0];
    result->area += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    result->mesh.triangles.push_back(triangle);
    result->mesh.material_uv.push_back(uv);
  }
}

// The signed area of a closed polygon (the shoelace formula).
double polygon_area(const std::vector<Vector2d>& boundary) {
  double twice = 0;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const Vector2d& a = boundary[i];
    const Vector2d& b = boundary[(i + 1) % boundary.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

} // namespace

int pieces_for(double length, double edge_length) {
  return std::max(
      1, static_cast<int>(std::ceil(length / (boundary_piece_fraction * edge_length) - 1e-9)));
}

PanelMesh mesh_panel(const garment::Panel& panel, const PanelMeshOptions& options) {
  const std::string where = "panel '" + panel.id + "'";
  check_mesh_options(where, options);
  OutlinePieces outline = outline_pieces(panel, options, where);
  int rounds = 0;
  const std::unique_ptr<Attempt> attempt = refine_panel(panel, options, outline, &rounds);
  const std::vector<int>& pieces = outline.pieces;
  const std::vector<std::vector<Vertex>>& outline_paths = attempt->outline_paths;

  // Number the vertices: the outline's first, in counter-clockwise order.
  PanelMesh result;
  result.rounds = rounds;
  VertexNumbering number{result.mesh, {}};
  std::vector<Vector2d> boundary;
  for (std::size_t l = 0; l < panel.outline.size(); ++l) {
    MeshedLine line;
    line.id = panel.outline[l].id;
    line.pieces = pieces[l];
    line.forced = outline.forced[l];
    line.split_by_mesher = outline_paths[l].size() != std::size_t(pieces[l]) + 1;
    for (Vertex v : outline_paths[l]) {
      line.vertices.push_back(number(v));
      if (v != outline_paths[l].back()) boundary.push_back(to_eigen(v->point()));
    }
    result.lines.push_back(std::move(line));
  }
  for (std::size_t l = 0; l < panel.interior.size(); ++l) {
    MeshedLine line;
    line.id = panel.interior[l].id;
    line.interior = true;
    line.pieces = int(attempt->interior[l].vertices.size()) - 1;
    for (Vertex v : walk_line(attempt->triangulation, attempt->interior[l]))
      line.vertices.push_back(number(v));
    result.lines.push_back(std::move(line));
  }
  add_triangles(*attempt, panel, options, number, &result);
  result.boundary_area = polygon_area(boundary);
  validate(result.mesh, where);
  return result;
}

} // namespace sartor
