// The bending models against beam theory, with references computed here:
// the Euler elastica by shooting (heavy cantilever, Peirce's test; end-shear
// cantilever of Sze, Liu & Lo 2004 with nu = 0) and the simply supported
// strip's 5 w L^4 / 384 D, on rectangle meshes of every diagonal pattern,
// cells of aspect 4, and irregular meshes (random diagonals, perturbed
// interior vertices) refined three times; the simply supported square plate
// (Navier's double series) on three Delaunay meshes; the slit annular plate
// of Sze, Liu & Lo (no closed form: their converged values).

#include "fem/cloth_problem.hpp"
#include "garment/pattern.hpp"
#include "mesh/generators.hpp"
#include "mesh/panel_mesher.hpp"
#include "solvers/statics.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

namespace sartor {
namespace {

// --- Elastica: theta'' = -(gamma (1 - s) + alpha) cos theta on s in [0, 1],
// theta(0) = 0 (clamped), theta'(1) = 0 (free end); gamma = w L^3 / D (own
// weight), alpha = P L^2 / D (end shear). RK4, shooting on theta'(0).
struct ElasticaTip {
  double droop = 0.0;      // vertical tip displacement / L
  double shortening = 0.0; // horizontal tip displacement / L
  double end_slope = 0.0;  // theta'(1), zero for the solution
};

ElasticaTip integrate(double gamma, double alpha, double start_slope) {
  constexpr int steps = 4000;
  const double h = 1.0 / steps;
  double theta = 0.0, slope = start_slope, x = 0.0, z = 0.0;
  const auto rhs = [&](double s, double th) { return -(gamma * (1.0 - s) + alpha) * std::cos(th); };
  for (int i = 0; i < steps; ++i) {
    const double s = i * h;
    const double k1t = slope, k1s = rhs(s, theta);
    const double k2t = slope + 0.5 * h * k1s, k2s = rhs(s + 0.5 * h, theta + 0.5 * h * k1t);
    const double k3t = slope + 0.5 * h * k2s, k3s = rhs(s + 0.5 * h, theta + 0.5 * h * k2t);
    const double k4t = slope + h * k3s, k4s = rhs(s + h, theta + h * k3t);
    // Position by Simpson's rule on the same step.
    const double next_theta = theta + h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    const double mid_theta = theta + 0.5 * h * k1t + h * h / 8.0 * k1s;
    x += h / 6.0 * (std::cos(theta) + 4.0 * std::cos(mid_theta) + std::cos(next_theta));
    z += h / 6.0 * (std::sin(theta) + 4.0 * std::sin(mid_theta) + std::sin(next_theta));
    slope += h / 6.0 * (k1s + 2 * k2s + 2 * k3s + k4s);
    theta = next_theta;
  }
  return {z, 1.0 - x, slope};
}

ElasticaTip elastica(double gamma, double alpha) {
  // theta'(1) grows with theta'(0) from -(gamma/2 + alpha) at 0: bisection on
  // [0, gamma/2 + alpha], where the end slope changes sign.
  double low = 0.0, high = gamma / 2.0 + alpha;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (integrate(gamma, alpha, mid).end_slope < 0.0 ? low : high) = mid;
  }
  return integrate(gamma, alpha, 0.5 * (low + high));
}

TEST(Elastica, LinearLimitsAndTabulatedValue) {
  // Small loads: w L^4 / 8 D and P L^3 / 3 D.
  EXPECT_NEAR(elastica(1e-3, 0.0).droop / (1e-3 / 8.0), 1.0, 1e-4);
  EXPECT_NEAR(elastica(0.0, 1e-3).droop / (1e-3 / 3.0), 1.0, 1e-4);
  // Bisshopp & Drucker (1945): P L^2 / EI = 1 gives 0.3017 L and 0.0566 L.
  EXPECT_NEAR(elastica(0.0, 1.0).droop, 0.3017, 2e-4);
  EXPECT_NEAR(elastica(0.0, 1.0).shortening, 0.0566, 2e-4);
}

// --- Meshes ---------------------------------------------------------------

// nx x ny cells on [0, width] x [0, height]; irregular: each cell's diagonal
// drawn at random and interior vertices moved by up to a quarter cell, but
// columns 0 and 1 kept straight (the clamp's band ends on a straight line).
TriangleMesh strip_mesh(double width, double height, int nx, int ny, bool irregular,
                        mesh::RectanglePattern pattern = mesh::RectanglePattern::right) {
  if (!irregular) return mesh::rectangle(width, height, nx, ny, pattern);
  std::mt19937_64 random(std::uint64_t(1000 * nx + ny));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double hx = width / nx, hy = height / ny;
  TriangleMesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      Eigen::Vector3d p(i * hx, j * hy, 0.0);
      if (i > 1 && i < nx && j > 0 && j < ny)
        p += Eigen::Vector3d(0.25 * hx * unit(random), 0.25 * hy * unit(random), 0.0);
      mesh.positions.push_back(p);
    }
  }
  const auto uv = [&](int v) { return Eigen::Vector2d(mesh.positions[std::size_t(v)].head<2>()); };
  const auto add = [&](int a, int b, int c) {
    mesh.triangles.push_back({a, b, c});
    mesh.material_uv.push_back({uv(a), uv(b), uv(c)});
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = b + nx + 1, d = a + nx + 1;
      if (unit(random) > 0.0) {
        add(a, b, c);
        add(a, c, d);
      } else {
        add(a, b, d);
        add(b, c, d);
      }
    }
  }
  return mesh;
}

ClothMaterial strip_material(double membrane, double rigidity, double density,
                             element::BendingModel model) {
  ClothMaterial m({TensionCurve::linear(membrane, "test"), TensionCurve::linear(membrane, "test"),
                   0.5 * membrane, 0.0});
  m.bending_stiffness = rigidity;
  m.areal_density = density;
  m.bending_model = model;
  return m;
}

// The vertex positions after a static solve in `steps` load increments.
std::vector<Eigen::Vector3d> solved_positions(const TriangleMesh& mesh,
                                              const ClothMaterial& material,
                                              const std::vector<int>& pins, const ClothLoads& loads,
                                              int steps) {
  ClothProblem problem(PETSC_COMM_WORLD, mesh, material, pins);
  problem.loads = loads;
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = steps;
  StaticReport report;
  EXPECT_EQ(solve_static(problem, x, options, &report), 0);
  EXPECT_TRUE(report.converged) << report.reason;
  std::vector<Eigen::Vector3d> positions;
  EXPECT_EQ(problem.gather_positions(x, &positions), 0);
  VecDestroy(&x);
  return positions;
}

// Mean displacement of the vertices at x = x_tip after a static solve.
Eigen::Vector3d tip_displacement(const TriangleMesh& mesh, const ClothMaterial& material,
                                 const std::vector<int>& pins, const ClothLoads& loads,
                                 double x_tip, int steps) {
  const std::vector<Eigen::Vector3d> positions =
      solved_positions(mesh, material, pins, loads, steps);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (std::abs(mesh.positions[v].x() - x_tip) > 1e-9) continue;
    sum += positions[v] - mesh.positions[v];
    ++count;
  }
  return sum / count;
}

std::vector<int> vertices_below(const TriangleMesh& mesh, double x_limit) {
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions[v].x() < x_limit) pins.push_back(int(v));
  return pins;
}

double observed_order(double coarse, double fine) {
  return std::log(std::abs(coarse) / std::abs(fine)) / std::log(2.0);
}

constexpr double gravity = 9.80665;

// --- Simply supported strip, linear range ---------------------------------

// Largest deflection of a 1 m strip on supports at both ends under its
// weight, relative to 5 w L^4 / 384 D, minus one.
double simply_supported_error(const TriangleMesh& mesh, element::BendingModel model) {
  const double rigidity = 1.0, density = 1e-3; // deflection 1.3e-4 L: linear
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions[v].x();
    if (x < 1e-9 || x > 1.0 - 1e-9) pins.push_back(int(v));
  }
  ClothProblem problem(PETSC_COMM_WORLD, mesh, strip_material(1e4, rigidity, density, model), pins);
  problem.loads.gravity = {0.0, 0.0, -gravity};
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticReport report;
  EXPECT_EQ(solve_static(problem, x, StaticOptions{}, &report), 0);
  EXPECT_TRUE(report.converged) << report.reason;
  std::vector<Eigen::Vector3d> positions;
  EXPECT_EQ(problem.gather_positions(x, &positions), 0);
  VecDestroy(&x);
  double deflection = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    deflection = std::max(deflection, mesh.positions[v].z() - positions[v].z());
  return deflection / (5.0 * density * gravity / (384.0 * rigidity)) - 1.0;
}

TEST(BendingVerification, SimplySupportedStripOnEveryPatternAndAspect) {
  struct Case {
    const char* name;
    TriangleMesh mesh;
  };
  using mesh::RectanglePattern;
  const std::vector<Case> cases = {
      {"alternating 40x4", mesh::rectangle(1.0, 0.1, 40, 4, RectanglePattern::alternating)},
      {"right 40x4", mesh::rectangle(1.0, 0.1, 40, 4, RectanglePattern::right)},
      {"perturbed 40x4", mesh::rectangle(1.0, 0.1, 40, 4, RectanglePattern::perturbed)},
      {"irregular 40x4", strip_mesh(1.0, 0.1, 40, 4, true)},
      {"alternating, cells 4 x longer across (40x1)",
       mesh::rectangle(1.0, 0.1, 40, 1, RectanglePattern::alternating)},
      {"alternating, cells 4 x longer along (10x4)",
       mesh::rectangle(1.0, 0.1, 10, 4, RectanglePattern::alternating)},
      {"perturbed, cells 4 x longer across (40x4, 0.4 wide)",
       mesh::rectangle(1.0, 0.4, 40, 4, RectanglePattern::perturbed)},
  };
  for (const Case& c : cases) {
    const double patch = simply_supported_error(c.mesh, element::BendingModel::patch);
    const double hinge = simply_supported_error(c.mesh, element::BendingModel::discrete_shell);
    const double quadratic = simply_supported_error(c.mesh, element::BendingModel::quadratic);
    std::printf("simply supported strip, %s: patch %+.3f %%, discrete shell %+.3f %%, quadratic "
                "%+.3f %%\n",
                c.name, 100 * patch, 100 * hinge, 100 * quadratic);
    EXPECT_LT(std::abs(patch), 0.01) << c.name;
  }
}

// --- Simply supported square plate, linear range ---------------------------

// Navier's double series for a simply supported square plate of side a under
// a uniform load q: w = 16 q / (pi^6 D) sum over odd m, n of
// sin(m pi x / a) sin(n pi y / a) / (m n (m^2 + n^2)^2 / a^4).
double navier_deflection(double x, double y, double a, double q, double rigidity) {
  const double pi = std::acos(-1.0);
  double sum = 0.0;
  for (int m = 1; m < 200; m += 2) {
    for (int n = 1; n < 200; n += 2) {
      const double mn2 = double(m * m + n * n);
      sum += std::sin(m * pi * x / a) * std::sin(n * pi * y / a) / (m * n * mn2 * mn2);
    }
  }
  return 16.0 * q * std::pow(a, 4) / (std::pow(pi, 6) * rigidity) * sum;
}

// The unit square as a pattern panel, triangulated by the Delaunay mesher
// (unstructured) with edges up to `edge_length`.
TriangleMesh delaunay_square(double edge_length) {
  const auto side = [](const char* id, double x0, double y0, double x1, double y1) {
    return nlohmann::json{{"id", id}, {"type", "straight"}, {"points", {{x0, y0}, {x1, y1}}}};
  };
  const nlohmann::json document = {{"format", "sartor-pattern"},
                                   {"version", 1},
                                   {"units", "m"},
                                   {"panels",
                                    {{{"id", "plate"},
                                      {"fabric", "silk"},
                                      {"tag", {{"cylinder", "torso"}, {"side", "front"}}},
                                      {"grain", {{"angle_deg", 0}}},
                                      {"outline",
                                       {side("bottom", 0, 0, 1, 0), side("right", 1, 0, 1, 1),
                                        side("top", 1, 1, 0, 1), side("left", 0, 1, 0, 0)}}}}}};
  const garment::Pattern pattern = garment::parse_pattern(document.dump(), "square.json");
  PanelMeshOptions options;
  options.edge_length = edge_length;
  return mesh_panel(pattern.panels.front(), options).mesh;
}

// The plate's mean deflection from the same series: 64 q a^4 / (pi^8 D) times
// the sum over odd m, n of 1 / (m^2 n^2 (m^2 + n^2)^2).
double navier_mean_deflection(double a, double q, double rigidity) {
  const double pi = std::acos(-1.0);
  double sum = 0.0;
  for (int m = 1; m < 400; m += 2) {
    for (int n = 1; n < 400; n += 2) {
      const double mn2 = double(m * m + n * n);
      sum += 1.0 / (double(m * m) * double(n * n) * mn2 * mn2);
    }
  }
  return 64.0 * q * std::pow(a, 4) / (std::pow(pi, 8) * rigidity) * sum;
}

struct PlateErrors {
  double centre = 0.0;     // at the vertex nearest the centre, against the series there
  double compliance = 0.0; // of the mean deflection (the load's work per q), a global measure
};

// Errors of the simply supported plate (boundary vertices pinned) under a
// uniform load, relative to Navier's series.
PlateErrors square_plate_errors(const TriangleMesh& mesh, element::BendingModel model) {
  const double rigidity = 1.0, density = 1e-3; // deflection 4e-5 of the side: linear
  std::vector<int> pins;
  std::size_t centre = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    if (std::min({p.x(), p.y(), 1.0 - p.x(), 1.0 - p.y()}) < 1e-9) pins.push_back(int(v));
    const Eigen::Vector3d middle(0.5, 0.5, 0.0);
    if ((p - middle).norm() < (mesh.positions[centre] - middle).norm()) centre = v;
  }
  ClothProblem problem(PETSC_COMM_WORLD, mesh, strip_material(1e4, rigidity, density, model), pins);
  problem.loads.gravity = {0.0, 0.0, -gravity};
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticReport report;
  EXPECT_EQ(solve_static(problem, x, StaticOptions{}, &report), 0);
  EXPECT_TRUE(report.converged) << report.reason;
  std::vector<Eigen::Vector3d> positions;
  EXPECT_EQ(problem.gather_positions(x, &positions), 0);
  VecDestroy(&x);
  const double q = density * gravity;
  const Eigen::Vector3d& p = mesh.positions[centre];
  const double reference = navier_deflection(p.x(), p.y(), 1.0, q, rigidity);
  // The integral of the piecewise-linear deflection: a third of each
  // triangle's area per corner (the load's work over q).
  double integral = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.positions[std::size_t(tri[0])];
    const double area = 0.5 * (mesh.positions[std::size_t(tri[1])] - a)
                                  .cross(mesh.positions[std::size_t(tri[2])] - a)
                                  .norm();
    for (const int v : tri)
      integral += area / 3.0 * (mesh.positions[std::size_t(v)].z() - positions[std::size_t(v)].z());
  }
  return {(p.z() - positions[centre].z()) / reference - 1.0,
          integral / navier_mean_deflection(1.0, q, rigidity) - 1.0};
}

TEST(BendingVerification, SimplySupportedSquarePlateOnDelaunayMeshes) {
  // Series checks: the centre deflection 0.00406235 q a^4 / D (Timoshenko);
  // the mean deflection by the midpoint rule on a 200 x 200 grid.
  EXPECT_NEAR(navier_deflection(0.5, 0.5, 1.0, 1.0, 1.0), 0.00406235, 1e-7);
  double mean = 0.0;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j)
      mean += navier_deflection((i + 0.5) / 200, (j + 0.5) / 200, 1.0, 1.0, 1.0) / 40000.0;
  EXPECT_NEAR(navier_mean_deflection(1.0, 1.0, 1.0) / mean, 1.0, 1e-4);
  std::vector<PlateErrors> patch;
  for (const double edge : {0.2, 0.1, 0.05, 0.025}) {
    const TriangleMesh mesh = delaunay_square(edge);
    patch.push_back(square_plate_errors(mesh, element::BendingModel::patch));
    const double hinge = square_plate_errors(mesh, element::BendingModel::discrete_shell).centre;
    const double quadratic = square_plate_errors(mesh, element::BendingModel::quadratic).centre;
    std::printf("simply supported square plate, Delaunay edges <= %g m (%zu triangles): patch "
                "%+.3f %% (mean deflection %+.3f %%), discrete shell %+.3f %%, quadratic "
                "%+.3f %%\n",
                edge, mesh.triangle_count(), 100 * patch.back().centre,
                100 * patch.back().compliance, 100 * hinge, 100 * quadratic);
  }
  std::printf("square plate, patch: observed orders %.2f, %.2f, %.2f (mean deflection %.2f, "
              "%.2f, %.2f)\n",
              observed_order(patch[0].centre, patch[1].centre),
              observed_order(patch[1].centre, patch[2].centre),
              observed_order(patch[2].centre, patch[3].centre),
              observed_order(patch[0].compliance, patch[1].compliance),
              observed_order(patch[1].compliance, patch[2].compliance),
              observed_order(patch[2].compliance, patch[3].compliance));
  // Measured -5.1, +0.50, -0.36, -0.22 %: on these non-nested Delaunay
  // meshes the error follows the mesh's irregularity (it changes sign; 0.7
  // between the two finest), and falls to -0.006 and +0.002 % on the finer
  // meshes of the benchmark below (the hinges stay 7 % too stiff).
  EXPECT_LT(std::abs(patch[3].centre), 0.005);
  EXPECT_LT(std::abs(patch[3].centre), std::abs(patch[2].centre));
  EXPECT_LT(std::abs(patch[2].centre), 0.2 * std::abs(patch[0].centre));
}

// A benchmark, not run by ctest (about a minute of CPU, 4 GB): the patch
// model's square plate on two more Delaunay meshes (edges <= 0.0125 and
// 0.00625 m, 33,262 and 134,110 triangles), for the observed orders between
// the finer meshes (docs/finite-elements.md).
// Run: sartor_verification_tests --gtest_also_run_disabled_tests
//      --gtest_filter='*DISABLED_SquarePlateOnFinerDelaunayMeshes'
TEST(BendingVerification, DISABLED_SquarePlateOnFinerDelaunayMeshes) {
  std::vector<PlateErrors> errors;
  for (const double edge : {0.1, 0.05, 0.025, 0.0125, 0.00625}) {
    const TriangleMesh mesh = delaunay_square(edge);
    errors.push_back(square_plate_errors(mesh, element::BendingModel::patch));
    std::printf("square plate, patch, edges <= %g m (%zu triangles): centre %+.4f %%, mean "
                "deflection %+.4f %%\n",
                edge, mesh.triangle_count(), 100 * errors.back().centre,
                100 * errors.back().compliance);
    if (errors.size() > 1) {
      const PlateErrors& coarse = errors[errors.size() - 2];
      std::printf("  observed orders: centre %.2f, mean deflection %.2f\n",
                  observed_order(coarse.centre, errors.back().centre),
                  observed_order(coarse.compliance, errors.back().compliance));
    }
  }
}

// --- Cantilevers ------------------------------------------------------------

// A strip of free length L clamped by a pinned band of one cell (columns 0
// and 1 of nx + 1), so that its cells are L / (nx - 1) long.
struct Cantilever {
  TriangleMesh mesh;
  std::vector<int> clamp;
  double tip_x;
};

Cantilever cantilever(double length, double width, int nx, int ny) {
  const double cell = length / (nx - 1);
  Cantilever c{strip_mesh(length + cell, width, nx, ny, true), {}, length + cell};
  c.clamp = vertices_below(c.mesh, 1.5 * cell);
  return c;
}

struct Refinement {
  int nx, ny;
};
constexpr Refinement cantilever_meshes[] = {{20, 2}, {40, 4}, {80, 8}};

// Relative droop error of the heavy cantilever at gamma = w L^3 / D.
double heavy_cantilever_error(double gamma, const Refinement& r, element::BendingModel model) {
  const double length = 1.0, rigidity = 1e-3;
  const Cantilever c = cantilever(length, 2.0 * r.ny * length / r.nx, r.nx, r.ny);
  ClothLoads loads;
  loads.gravity = {0.0, 0.0, -gravity};
  const double density = gamma * rigidity / (gravity * length * length * length);
  const Eigen::Vector3d tip =
      tip_displacement(c.mesh, strip_material(1e3, rigidity, density, model), c.clamp, loads,
                       c.tip_x, gamma > 10 ? 16 : 8);
  return -tip.z() / (length * elastica(gamma, 0.0).droop) - 1.0;
}

TEST(BendingVerification, HeavyCantileverConvergesToTheElastica) {
  for (const double gamma : {1.0, 8.0, 32.0}) {
    std::vector<double> errors;
    for (const Refinement& r : cantilever_meshes)
      errors.push_back(heavy_cantilever_error(gamma, r, element::BendingModel::patch));
    const double hinge =
        heavy_cantilever_error(gamma, cantilever_meshes[2], element::BendingModel::discrete_shell);
    std::printf("heavy cantilever, gamma %g: patch droop errors %+.3f %%, %+.3f %%, %+.3f %% "
                "(orders %.2f, %.2f); discrete shell on the finest %+.3f %%\n",
                gamma, 100 * errors[0], 100 * errors[1], 100 * errors[2],
                observed_order(errors[0], errors[1]), observed_order(errors[1], errors[2]),
                100 * hinge);
    EXPECT_LT(std::abs(errors[2]), 0.01) << "gamma " << gamma;
    // At least first order over the three meshes (2 measured).
    EXPECT_GT(observed_order(errors[0], errors[2]) / 2.0, 1.0) << "gamma " << gamma;
  }
}

// --- Heavy cantilever with a bilinear moment-curvature curve ----------------

// M = D1 k up to k1, then slope D2 (measured fabrics soften or stiffen);
// its inverse k(M).
struct Bilinear {
  double d1, d2, k1;
  double curvature(double moment) const {
    return moment <= d1 * k1 ? moment / d1 : k1 + (moment - d1 * k1) / d2;
  }
};

// The elastica of a heavy cantilever (length 1, weight w per length) with
// that curve: theta' = k(M), M' = -w (1 - s) cos theta, theta(0) = 0,
// M(1) = 0; RK4, shooting on M(0) in [0, w / 2]. Returns the tip droop.
double bilinear_elastica_droop(const Bilinear& curve, double w) {
  const auto shoot = [&](double start_moment, double* droop) {
    constexpr int steps = 8000;
    const double h = 1.0 / steps;
    double theta = 0.0, moment = start_moment, z = 0.0;
    const auto f = [&](double s, double th, double m) {
      return Eigen::Vector3d(curve.curvature(m), -w * (1.0 - s) * std::cos(th), std::sin(th));
    };
    for (int i = 0; i < steps; ++i) {
      const double s = i * h;
      const Eigen::Vector3d k1 = f(s, theta, moment);
      const Eigen::Vector3d k2 = f(s + h / 2, theta + h / 2 * k1[0], moment + h / 2 * k1[1]);
      const Eigen::Vector3d k3 = f(s + h / 2, theta + h / 2 * k2[0], moment + h / 2 * k2[1]);
      const Eigen::Vector3d k4 = f(s + h, theta + h * k3[0], moment + h * k3[1]);
      const Eigen::Vector3d step = h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      theta += step[0];
      moment += step[1];
      z += step[2];
    }
    if (droop) *droop = z;
    return moment; // M(1), increasing with M(0)
  };
  double low = 0.0, high = w / 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (shoot(mid, nullptr) < 0.0 ? low : high) = mid;
  }
  double droop = 0.0;
  shoot(0.5 * (low + high), &droop);
  return droop;
}

TEST(BendingVerification, HeavyCantileverWithBilinearMomentCurve) {
  // Rigidity 1e-3 N m up to 1 1/m, a quarter of it beyond (softening), and
  // twice it (stiffening); the weight puts the root well past the kink.
  const double gravity_load = 8e-3; // w = gamma D1 / L^3 with gamma = 8
  const Refinement fine = cantilever_meshes[2];
  const Cantilever c = cantilever(1.0, 2.0 * fine.ny / fine.nx, fine.nx, fine.ny);
  for (const double ratio : {0.25, 2.0}) {
    const Bilinear curve{1e-3, ratio * 1e-3, 1.0};
    const double reference = bilinear_elastica_droop(curve, gravity_load);
    // Linear: the elastica at gamma = 8 (droop 0.56 L); the kink changes it.
    const double linear = elastica(8.0, 0.0).droop;
    ClothMaterial material =
        strip_material(1e3, 1e-3, gravity_load / gravity, element::BendingModel::patch);
    const MomentCurve moment = MomentCurve::piecewise(
        {{curve.k1, curve.d1 * curve.k1}, {curve.k1 + 10.0, curve.d1 * curve.k1 + 10.0 * curve.d2}},
        "test");
    material.bending_curves = std::make_shared<const FabricBending>(
        FabricBending{moment, moment, MomentCurve::linear(0.5e-3, "test")});
    ClothLoads loads;
    loads.gravity = {0.0, 0.0, -gravity};
    const Eigen::Vector3d tip = tip_displacement(c.mesh, material, c.clamp, loads, c.tip_x, 8);
    const double error = -tip.z() / reference - 1.0;
    std::printf("heavy cantilever, bilinear curve (slope ratio %g beyond 1 1/m): elastica droop "
                "%.4f L (linear %.4f L), patch on %dx%d %+.3f %%\n",
                ratio, reference, linear, fine.nx, fine.ny, 100 * error);
    EXPECT_GT(std::abs(reference / linear - 1.0), 0.05); // the kink matters
    EXPECT_LT(std::abs(error), 0.02);
  }
}

// Sze, Liu & Lo (2004) problem 1: L = 10, width 1, t = 0.1, E = 1.2e6, nu = 0
// (D = E t^3 / 12 = 100 N m, membrane E t = 1.2e5 N/m), end shear P.
Eigen::Vector3d sze_tip(double load, const Refinement& r, element::BendingModel model) {
  const double length = 10.0, width = 1.0;
  const Cantilever c = cantilever(length, width, r.nx, r.ny);
  // The end shear as a uniform line load on the tip edge (trapezoidal shares).
  ClothLoads loads;
  for (int j = 0; j <= r.ny; ++j) {
    const int vertex = j * (r.nx + 1) + r.nx;
    const double share = (j == 0 || j == r.ny) ? 0.5 : 1.0;
    loads.point_forces.push_back({vertex, Eigen::Vector3d(0.0, 0.0, load * share / r.ny)});
  }
  return tip_displacement(c.mesh, strip_material(1.2e5, 100.0, 0.0, model), c.clamp, loads, c.tip_x,
                          2 * int(load) + 4);
}

TEST(BendingVerification, SzeEndShearCantileverMatchesTheElastica) {
  for (const double load : {1.0, 2.0, 4.0}) {
    const ElasticaTip reference = elastica(0.0, load * 100.0 / 100.0);
    std::vector<Eigen::Vector2d> errors;
    for (const Refinement& r : cantilever_meshes) {
      const Eigen::Vector3d tip = sze_tip(load, r, element::BendingModel::patch);
      errors.emplace_back(-tip.x() / (10.0 * reference.shortening) - 1.0,
                          tip.z() / (10.0 * reference.droop) - 1.0);
    }
    const Eigen::Vector3d hinge =
        sze_tip(load, cantilever_meshes[2], element::BendingModel::discrete_shell);
    std::printf("Sze end shear P = %g: elastica tip (%.4f, %.4f) m; patch errors horizontal "
                "%+.3f %%, %+.3f %%, %+.3f %%, vertical %+.3f %%, %+.3f %%, %+.3f %% (orders "
                "%.2f, %.2f); discrete shell on the finest %+.3f %%, %+.3f %%\n",
                load, 10.0 * reference.shortening, 10.0 * reference.droop, 100 * errors[0].x(),
                100 * errors[1].x(), 100 * errors[2].x(), 100 * errors[0].y(), 100 * errors[1].y(),
                100 * errors[2].y(), observed_order(errors[0].y(), errors[1].y()),
                observed_order(errors[1].y(), errors[2].y()),
                100 * (-hinge.x() / (10.0 * reference.shortening) - 1.0),
                100 * (hinge.z() / (10.0 * reference.droop) - 1.0));
    if (load == 4.0) {
      EXPECT_LT(errors[2].cwiseAbs().maxCoeff(), 0.005);
    } else {
      EXPECT_LT(errors[2].cwiseAbs().maxCoeff(), 0.01);
    }
  }
}

// --- Slit annular plate (Sze, Liu & Lo 2004) ---------------------------------

// An annulus of radii 6 and 10, slit along +x, E = 21e6, nu = 0, t = 0.03
// (membrane E t = 6.3e5 N/m, D = E t^3 / 12 = 47.25 N m), clamped along one
// edge of the slit and lifted by 0.8 N/m along the other. Sze et al.'s values
// at full load (S4R shells, 10 x 80; no closed form exists): the lift of the
// loaded edge's inner corner A (r = 6) and outer corner B (r = 10).
constexpr double sze_slit_plate_wa = 13.891, sze_slit_plate_wb = 17.528;

struct SlitPlateLift {
  double inner = 0.0, outer = 0.0; // W_A, W_B
};

// The plate with the patch model on 4 x 32 free cells refined `refinements`
// times, clamped by a pinned sector one coarse cell wide beyond the slit
// (angles -11.25..0 degrees, overlapping the loaded end in the plane), in 40
// load steps. The start placement rises by 1 um along a helix to the loaded
// edge, which tells the slit's two edges apart.
SlitPlateLift slit_annular_plate(int refinements) {
  const double pi = std::acos(-1.0), lift = 1e-6, line_load = 0.8;
  const TriangleMesh mesh = mesh::annulus(6.0, 10.0, 4, 33, -pi / 16.0, 2.0 * pi,
                                          mesh::RectanglePattern::alternating, refinements, lift);
  std::vector<int> clamp;
  std::vector<std::pair<double, int>> loaded; // radius, vertex
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    if (std::abs(p.z()) < 1e-9 && p.y() < 1e-9) clamp.push_back(int(v));
    if (std::abs(p.y()) < 1e-9 && p.z() > 0.5 * lift) loaded.emplace_back(p.x(), int(v));
  }
  std::sort(loaded.begin(), loaded.end());
  // The line load's consistent shares: half of each edge to either end.
  ClothLoads loads;
  for (std::size_t i = 0; i + 1 < loaded.size(); ++i) {
    const double half = 0.5 * line_load * (loaded[i + 1].first - loaded[i].first);
    loads.point_forces.push_back({loaded[i].second, Eigen::Vector3d(0.0, 0.0, half)});
    loads.point_forces.push_back({loaded[i + 1].second, Eigen::Vector3d(0.0, 0.0, half)});
  }
  const std::vector<Eigen::Vector3d> positions = solved_positions(
      mesh, strip_material(6.3e5, 47.25, 0.0, element::BendingModel::patch), clamp, loads, 40);
  return {positions[std::size_t(loaded.front().second)].z(),
          positions[std::size_t(loaded.back().second)].z()};
}

TEST(BendingVerification, SlitAnnularPlateMatchesSzeLiuLo) {
  // 8 x 64 free cells (1,056 triangles); measured -2.7 % (A) and -2.1 % (B),
  // converging at orders 1.1 to 1.4 on finer meshes (docs/finite-elements.md).
  const SlitPlateLift patch = slit_annular_plate(1);
  const double error_a = patch.inner / sze_slit_plate_wa - 1.0;
  const double error_b = patch.outer / sze_slit_plate_wb - 1.0;
  std::printf("slit annular plate, 8 x 64 cells, patch: W_A %.4f (%+.2f %%), W_B %.4f (%+.2f %%)\n",
              patch.inner, 100 * error_a, patch.outer, 100 * error_b);
  EXPECT_LT(std::abs(error_a), 0.05);
  EXPECT_LT(std::abs(error_b), 0.05);
  // The twist lifts the outer corner more than the inner one.
  EXPECT_GT(patch.outer - patch.inner, 0.5 * (sze_slit_plate_wb - sze_slit_plate_wa));
}

} // namespace
} // namespace sartor
