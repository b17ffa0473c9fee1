#include "mesh/generators.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <unordered_map>

namespace sartor::mesh {

namespace {

constexpr double pi = 3.14159265358979323846;

void require_positive(const char* generator, const char* name, double value, const char* unit) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string(generator) + ": " + name + " must be a positive finite number (" +
                     unit + "), got " + format_number(value));
  }
}

void require_at_least(const char* generator, const char* name, int value, int minimum) {
  if (value < minimum) {
    throw InputError(std::string(generator) + ": " + name + " must be at least " +
                     std::to_string(minimum) + ", got " + std::to_string(value));
  }
}

// Vertex and triangle counts must fit the mesh's int indices.
void require_int_size(const char* generator, std::int64_t vertices, std::int64_t triangles) {
  constexpr std::int64_t limit = std::numeric_limits<int>::max();
  if (vertices > limit || triangles > limit) {
    throw InputError(std::string(generator) + ": " + std::to_string(vertices) + " vertices and " +
                     std::to_string(triangles) +
                     " triangles are more than the mesh's indices can hold");
  }
}

// length * i / n, exactly length at i = n.
double fraction(double length, int i, int n) {
  return i == n ? length : length * static_cast<double>(i) / static_cast<double>(n);
}

// Uniform in [0, 1) from the generator's raw 64 bits: the same numbers on
// every platform (std::uniform_real_distribution is implementation-defined).
double unit_random(std::mt19937_64& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

void add_triangle(TriangleMesh& mesh, std::array<int, 3> vertices,
                  const std::array<Eigen::Vector2d, 3>& uv) {
  mesh.triangles.push_back(vertices);
  mesh.material_uv.push_back(uv);
}

// A triangle whose uv is the (x, y) of its vertices' positions.
void add_flat_triangle(TriangleMesh& mesh, std::array<int, 3> vertices) {
  std::array<Eigen::Vector2d, 3> uv;
  for (std::size_t c = 0; c < 3; ++c)
    uv[c] = mesh.positions[static_cast<std::size_t>(vertices[c])].head<2>();
  add_triangle(mesh, vertices, uv);
}

} // namespace

RectanglePattern rectangle_pattern(const std::string& name) {
  if (name == "alternating") return RectanglePattern::alternating;
  if (name == "right") return RectanglePattern::right;
  if (name == "perturbed") return RectanglePattern::perturbed;
  throw InputError("unknown rectangle pattern '" + name +
                   "' (expected alternating, right or perturbed)");
}

TriangleMesh rectangle(double width, double height, int nx, int ny, RectanglePattern pattern) {
  require_positive("rectangle", "width", width, "m");
  require_positive("rectangle", "height", height, "m");
  require_at_least("rectangle", "nx", nx, 1);
  require_at_least("rectangle", "ny", ny, 1);
  require_int_size("rectangle", (std::int64_t{nx} + 1) * (std::int64_t{ny} + 1),
                   2 * std::int64_t{nx} * std::int64_t{ny});

  TriangleMesh mesh;
  const int row = nx + 1;
  mesh.positions.reserve(static_cast<std::size_t>(row) * static_cast<std::size_t>(ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.positions.emplace_back(fraction(width, i, nx), fraction(height, j, ny), 0.0);

  if (pattern == RectanglePattern::perturbed) {
    // Offsets inside an ellipse of a quarter spacing: a triangle's height
    // (at least spacing / sqrt(2) in the unit cell) cannot close.
    std::mt19937_64 engine(20240611);
    const double ax = 0.25 * width / nx;
    const double ay = 0.25 * height / ny;
    for (int j = 1; j < ny; ++j) {
      for (int i = 1; i < nx; ++i) {
        double dx = 0.0;
        double dy = 0.0;
        do {
          dx = 2.0 * unit_random(engine) - 1.0;
          dy = 2.0 * unit_random(engine) - 1.0;
        } while (dx * dx + dy * dy > 1.0);
        auto& p = mesh.positions[static_cast<std::size_t>(j * row + i)];
        p.x() += ax * dx;
        p.y() += ay * dy;
      }
    }
  }

  mesh.triangles.reserve(2 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  mesh.material_uv.reserve(mesh.triangles.capacity());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = j * row + i; // (x0, y0)
      const int b = a + 1;       // (x1, y0)
      const int c = b + row;     // (x1, y1)
      const int d = a + row;     // (x0, y1)
      const bool rising = pattern == RectanglePattern::right || (i + j) % 2 == 0;
      if (rising) {
        add_flat_triangle(mesh, {a, b, c});
        add_flat_triangle(mesh, {a, c, d});
      } else {
        add_flat_triangle(mesh, {a, b, d});
        add_flat_triangle(mesh, {b, c, d});
      }
    }
  }
  validate(mesh, "rectangle");
  return mesh;
}

namespace {

// The disk without argument checks; `generator` names the caller in errors.
TriangleMesh disk_pattern(double radius, int rings, const char* generator) {
  require_int_size(generator, 1 + 3 * std::int64_t{rings} * (std::int64_t{rings} + 1),
                   6 * std::int64_t{rings} * std::int64_t{rings});
  TriangleMesh mesh;
  mesh.positions.reserve(static_cast<std::size_t>(1 + 3 * rings * (rings + 1)));
  mesh.positions.emplace_back(0.0, 0.0, 0.0);
  for (int k = 1; k <= rings; ++k) {
    const double r = fraction(radius, k, rings);
    const int n = 6 * k;
    for (int j = 0; j < n; ++j) {
      const double angle = 2.0 * pi * j / n;
      mesh.positions.emplace_back(r * std::cos(angle), r * std::sin(angle), 0.0);
    }
  }
  const auto ring_start = [](int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); };

  mesh.triangles.reserve(static_cast<std::size_t>(6 * rings * rings));
  mesh.material_uv.reserve(mesh.triangles.capacity());
  for (int k = 1; k <= rings; ++k) {
    const int inner_start = ring_start(k - 1);
    const int outer_start = ring_start(k);
    const int inner_count = k == 1 ? 1 : 6 * (k - 1);
    const int outer_count = 6 * k;
    const auto inner = [&](int i) { return inner_start + i % inner_count; };
    const auto outer = [&](int j) { return outer_start + j % outer_count; };
    if (k == 1) {
      for (int j = 0; j < outer_count; ++j)
        add_flat_triangle(mesh, {0, outer(j), outer(j + 1)});
      continue;
    }
    // Walk both rings by angle, always closing the triangle whose next
    // vertex comes first (the outer one on ties): inner + outer triangles.
    int i = 0;
    int j = 0;
    while (i < inner_count || j < outer_count) {
      const bool outer_next =
          j < outer_count && (i == inner_count || std::int64_t{j + 1} * inner_count <=
                                                      std::int64_t{i + 1} * outer_count);
      if (outer_next) {
        add_flat_triangle(mesh, {inner(i), outer(j), outer(j + 1)});
        ++j;
      } else {
        add_flat_triangle(mesh, {inner(i), outer(j), inner(i + 1)});
        ++i;
      }
    }
  }
  return mesh;
}

} // namespace

TriangleMesh disk(double radius, int rings) {
  require_positive("disk", "radius", radius, "m");
  require_at_least("disk", "rings", rings, 1);
  TriangleMesh mesh = disk_pattern(radius, rings, "disk");
  validate(mesh, "disk");
  return mesh;
}

TriangleMesh cylinder_band(double radius, double height, int segments, int rows,
                           BandLength length) {
  require_positive("cylinder_band", "radius", radius, "m");
  require_positive("cylinder_band", "height", height, "m");
  require_at_least("cylinder_band", "segments", segments, 3);
  require_at_least("cylinder_band", "rows", rows, 1);
  require_int_size("cylinder_band", std::int64_t{segments} * (std::int64_t{rows} + 1),
                   2 * std::int64_t{segments} * std::int64_t{rows});

  const double circumference = length == BandLength::arc
                                   ? 2.0 * pi * radius
                                   : segments * 2.0 * radius * std::sin(pi / segments);
  TriangleMesh mesh;
  mesh.positions.reserve(static_cast<std::size_t>(segments) * static_cast<std::size_t>(rows + 1));
  for (int i = 0; i <= rows; ++i) {
    const double z = fraction(height, i, rows);
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * pi * j / segments;
      mesh.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
    }
  }
  // Column j runs from u(j) to u(j + 1); the last one ends at the seam, on
  // vertex 0 of its row but at u = circumference.
  const auto vertex = [&](int j, int i) { return i * segments + j % segments; };
  const auto uv = [&](int j, int i) {
    return Eigen::Vector2d(fraction(circumference, j, segments), fraction(height, i, rows));
  };
  mesh.triangles.reserve(2 * static_cast<std::size_t>(segments) * static_cast<std::size_t>(rows));
  mesh.material_uv.reserve(mesh.triangles.capacity());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < segments; ++j) {
      const std::array<int, 2> a{j, i};
      const std::array<int, 2> b{j + 1, i};
      const std::array<int, 2> c{j + 1, i + 1};
      const std::array<int, 2> d{j, i + 1};
      const auto add = [&](const std::array<int, 2>& p, const std::array<int, 2>& q,
                           const std::array<int, 2>& r) {
        add_triangle(mesh, {vertex(p[0], p[1]), vertex(q[0], q[1]), vertex(r[0], r[1])},
                     {uv(p[0], p[1]), uv(q[0], q[1]), uv(r[0], r[1])});
      };
      if ((i + j) % 2 == 0) {
        add(a, b, c);
        add(a, c, d);
      } else {
        add(a, b, d);
        add(b, c, d);
      }
    }
  }
  validate(mesh, "cylinder_band");
  return mesh;
}

TriangleMesh sphere_cap(double sphere_radius, double cap_angle, int rings) {
  require_positive("sphere_cap", "sphere_radius", sphere_radius, "m");
  if (!(cap_angle > 0.0 && cap_angle < pi)) {
    throw InputError("sphere_cap: cap_angle must lie strictly between 0 and pi (rad), got " +
                     format_number(cap_angle));
  }
  require_at_least("sphere_cap", "rings", rings, 1);
  TriangleMesh mesh = disk_pattern(sphere_radius * cap_angle, rings, "sphere_cap");
  for (auto& p : mesh.positions) {
    const double r = p.head<2>().norm();
    const double polar = r / sphere_radius;
    const double scale = r > 0.0 ? sphere_radius * std::sin(polar) / r : 0.0;
    p = Eigen::Vector3d(scale * p.x(), scale * p.y(), sphere_radius * std::cos(polar));
  }
  validate(mesh, "sphere_cap");
  return mesh;
}

TriangleMesh refine(const TriangleMesh& mesh) {
  validate(mesh, "refine");
  require_int_size("refine",
                   static_cast<std::int64_t>(mesh.vertex_count()) +
                       3 * static_cast<std::int64_t>(mesh.triangle_count()),
                   4 * static_cast<std::int64_t>(mesh.triangle_count()));
  TriangleMesh fine;
  fine.positions = mesh.positions;
  std::unordered_map<std::uint64_t, int> midpoints;
  midpoints.reserve(3 * mesh.triangle_count());
  const auto midpoint = [&](int a, int b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    const auto [it, inserted] =
        midpoints.try_emplace(lo << 32 | hi, static_cast<int>(fine.positions.size()));
    if (inserted) {
      fine.positions.push_back(0.5 * (mesh.positions[static_cast<std::size_t>(a)] +
                                      mesh.positions[static_cast<std::size_t>(b)]));
    }
    return it->second;
  };
  fine.triangles.reserve(4 * mesh.triangle_count());
  fine.material_uv.reserve(4 * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& v = mesh.triangles[t];
    const auto& uv = mesh.material_uv[t];
    const std::array<int, 3> m{midpoint(v[0], v[1]), midpoint(v[1], v[2]), midpoint(v[2], v[0])};
    const std::array<Eigen::Vector2d, 3> muv{0.5 * (uv[0] + uv[1]), 0.5 * (uv[1] + uv[2]),
                                             0.5 * (uv[2] + uv[0])};
    add_triangle(fine, {v[0], m[0], m[2]}, {uv[0], muv[0], muv[2]});
    add_triangle(fine, {m[0], v[1], m[1]}, {muv[0], uv[1], muv[1]});
    add_triangle(fine, {m[2], m[1], v[2]}, {muv[2], muv[1], uv[2]});
    add_triangle(fine, {m[0], m[1], m[2]}, {muv[0], muv[1], muv[2]});
  }
  if (!mesh.material_ids.empty()) {
    fine.material_ids.reserve(4 * mesh.triangle_count());
    for (const int id : mesh.material_ids)
      fine.material_ids.insert(fine.material_ids.end(), 4, id);
  }
  // A crease's two halves keep its rest angle.
  for (const CreaseEdge& crease : mesh.creases) {
    const int m = midpoint(crease.a, crease.b);
    fine.creases.push_back({crease.a, m, crease.rest_angle, crease.stiffness_factor});
    fine.creases.push_back({m, crease.b, crease.rest_angle, crease.stiffness_factor});
  }
  return fine;
}

TriangleMesh annulus(double inner_radius, double outer_radius, int rings, int segments,
                     double start_angle, double end_angle, RectanglePattern pattern,
                     int refinements, double lift) {
  require_positive("annulus", "inner_radius", inner_radius, "m");
  if (!(std::isfinite(outer_radius) && outer_radius > inner_radius)) {
    throw InputError("annulus: outer_radius must be a finite number above inner_radius (" +
                     format_number(inner_radius) + " m), got " + format_number(outer_radius));
  }
  const double span = end_angle - start_angle;
  if (!(std::isfinite(start_angle) && std::isfinite(span) && span > 0.0 && span <= 4.0 * pi)) {
    throw InputError("annulus: the angles must be finite with 0 < end_angle - start_angle <= 4 "
                     "pi (rad), got " +
                     format_number(start_angle) + " to " + format_number(end_angle));
  }
  if (!std::isfinite(lift) || (lift != 0.0 && !(end_angle > 0.0))) {
    throw InputError("annulus: lift must be finite, and 0 unless end_angle > 0, got lift " +
                     format_number(lift) + " m and end_angle " + format_number(end_angle));
  }
  require_at_least("annulus", "rings", rings, 1);
  require_at_least("annulus", "segments", segments, 1);
  require_at_least("annulus", "refinements", refinements, 0);
  TriangleMesh mesh = rectangle(1.0, 1.0, rings, segments, pattern);
  // A perturbed grid line at angle 0 (a slit's clamp) moves only along itself.
  const double zero_row = -start_angle / span * segments;
  if (pattern == RectanglePattern::perturbed && zero_row > 0.0 && zero_row < segments &&
      std::abs(zero_row - std::round(zero_row)) < 1e-9) {
    const int row = static_cast<int>(std::round(zero_row));
    for (int i = 0; i <= rings; ++i)
      mesh.positions[static_cast<std::size_t>(row * (rings + 1) + i)].y() =
          fraction(1.0, row, segments);
  }
  for (int level = 0; level < refinements; ++level)
    mesh = refine(mesh);
  // (radial, angular) fractions to the plane: orientation kept (the polar
  // map's Jacobian determinant is r > 0); z holds the angle until the lift,
  // and uv is set from the mapped positions.
  const auto map = [&](const Eigen::Vector3d& p) {
    const double r = inner_radius + p.x() * (outer_radius - inner_radius);
    const double angle = p.y() == 1.0 ? end_angle : start_angle + p.y() * span;
    return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), angle);
  };
  for (auto& p : mesh.positions)
    p = map(p);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c)
      mesh.material_uv[t][c] =
          mesh.positions[static_cast<std::size_t>(mesh.triangles[t][c])].head<2>();
  }
  for (auto& p : mesh.positions)
    p.z() = lift == 0.0 ? 0.0 : lift * std::max(p.z(), 0.0) / end_angle;
  validate(mesh, "annulus");
  return mesh;
}

} // namespace sartor::mesh
