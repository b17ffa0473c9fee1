// The certificate of a static equilibrium (solvers/certificate.hpp): each check
// against a reference computed here (weights, depths, crossings from the
// geometry; the buckling of a strip from Euler's load; the modes of a
// stretched membrane and of a free sheet).

#include "contact/analytic_shapes.hpp"
#include "contact/body.hpp"
#include "mesh/generators.hpp"
#include "solvers/certificate.hpp"
#include "solvers/statics.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <tuple>

namespace sartor {
namespace {

constexpr double gravity = 9.80665;

ClothMaterial fabric(double modulus, double bending, double density) {
  ClothMaterial m({TensionCurve::linear(modulus, "test"), TensionCurve::linear(modulus, "test"),
                   0.1 * modulus, 0.0});
  m.bending_stiffness = bending;
  m.areal_density = density;
  return m;
}

std::vector<int> vertices_where(const TriangleMesh& mesh, bool (*select)(const Eigen::Vector3d&)) {
  std::vector<int> chosen;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (select(mesh.positions[v])) chosen.push_back(int(v));
  return chosen;
}

// A 0.2 m sheet of 10 x 10 cells laid flat on the pole of a sphere of
// radius 1 m (its centre half the offset deep in the contact layer), with
// friction, solved statically: its edges (2 cm, 2.8 cm diagonals) cut
// chords at most 0.1 mm below the sphere, a tenth of the offset. Stiff
// enough in bending (1e-3 N m) that it bends onto the sphere without the
// in-plane compression of a wrap, which no friction would hold.
struct SheetOnSphere {
  static constexpr double radius = 1.0, side = 0.2, offset = 1e-3, density = 0.2;
  TriangleMesh mesh;
  std::unique_ptr<ClothProblem> problem;
  Vec x = nullptr;
  SheetOnSphere() {
    mesh = mesh::rectangle(side, side, 10, 10);
    for (auto& p : mesh.positions)
      p += Eigen::Vector3d(-0.5 * side, -0.5 * side, radius + 0.5 * offset);
    problem = std::make_unique<ClothProblem>(PETSC_COMM_WORLD, mesh, fabric(3000.0, 0.001, density),
                                             std::vector<int>{});
    problem->loads.gravity = {0.0, 0.0, -gravity};
    problem->contact.offset = offset;
    contact::Body ball("ball", std::make_shared<contact::Sphere>(Eigen::Vector3d::Zero(), radius),
                       Eigen::Vector3d::Zero());
    ball.friction = {0.5, 0.4};
    problem->bodies.push_back(ball);
    EXPECT_EQ(problem->create_solution(&x), 0);
  }
  ~SheetOnSphere() { VecDestroy(&x); }
  // Statics with lagged friction anchors: every solve ends by sliding the
  // anchors whose spring pulls beyond the cone, which unbalances the state
  // again; solves from there until the anchors hold (the residual after the
  // update is below 1e-9 N, 1.3e-8 of the weight).
  void solve() {
    StaticOptions options;
    options.load_steps = 4;
    for (int round = 0; round < 30; ++round) {
      StaticReport report;
      ASSERT_EQ(solve_static(*problem, x, options, &report), 0);
      ASSERT_TRUE(report.converged) << report.reason;
      if (report.final_residual_norm < 1e-9) return;
      options.start_load_factor = problem->load_factor;
      options.load_steps = 1;
    }
    FAIL() << "the friction anchors still slide";
  }
  // The smallest signed distance of a vertex to the sphere, m.
  double min_distance() {
    std::vector<Eigen::Vector3d> positions;
    EXPECT_EQ(problem->gather_positions(x, &positions), 0);
    double lowest = 1e30;
    for (const auto& p : positions)
      lowest = std::min(lowest, p.norm() - radius);
    MPI_Bcast(&lowest, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
    return lowest;
  }
};

TEST(Certificate, SheetRestingOnASpherePasses) {
  SheetOnSphere sheet;
  sheet.solve();
  Certificate c;
  ASSERT_EQ(certify(*sheet.problem, sheet.x, {}, &c), 0);
  // No pins: every vertex is free and the load is the whole weight.
  const double weight =
      SheetOnSphere::density * SheetOnSphere::side * SheetOnSphere::side * gravity;
  EXPECT_NEAR(c.reference_force, weight, 1e-9 * weight);
  EXPECT_LT(c.relative_residual, 1e-6);
  EXPECT_GT(c.min_distance, 0.0);
  EXPECT_NEAR(c.min_distance, sheet.min_distance(), 1e-12);
  EXPECT_EQ(c.edges, 10 * 11 * 2 + 10 * 10);
  EXPECT_EQ(c.edges_inside, 0);
  // The patch around the pole: sticking inside, sliding at its rim.
  EXPECT_GE(c.coulomb.contacts, 9);
  EXPECT_EQ(c.coulomb.sticking + c.coulomb.sliding, c.coulomb.contacts);
  EXPECT_TRUE(c.coulomb.passed()) << "worst |f_t| / mu_s f_n " << c.coulomb.worst_ratio;
  EXPECT_TRUE(c.placement.passed());
  EXPECT_NEAR(c.placement.carried_share.at(0), 1.0, 1e-3);
  EXPECT_TRUE(c.stability.assessed);
  EXPECT_EQ(c.stability.negative, 0);
  EXPECT_TRUE(c.certified()) << c.verdict();
}

// Without friction nothing holds the sheet on the sphere's top: turned
// rigidly about the sphere's centre by phi, its centre of mass (a distance
// r > 0 above the centre) drops by r (1 - cos phi): two directions of
// descent (the two horizontal axes), turning about the vertical costs nothing.
TEST(Certificate, SheetOnAFrictionlessSphereIsASaddle) {
  SheetOnSphere sheet;
  sheet.problem->bodies.front().friction = {0.0, 0.0};
  sheet.solve();
  Certificate c;
  ASSERT_EQ(certify(*sheet.problem, sheet.x, {}, &c), 0);
  EXPECT_LT(c.relative_residual, 1e-6);
  ASSERT_TRUE(c.stability.assessed);
  EXPECT_EQ(c.stability.negative, 2);
  EXPECT_EQ(c.stability.zero_modes, 1);
  EXPECT_TRUE(c.saddle());
}

// A 0.1 m sheet of 4 x 4 cells squeezed between two horizontal plates 1 mm
// apart, 0.5 mm from each (half into its contact offset), its weight pulling
// along them (gravity along x). Both plates push every vertex with the same
// normal force, so its net normal force is zero; the friction of each plate,
// within that plate's own cone, holds the weight. Coulomb's law is checked
// plate by plate: the vertex's tangential force against a cone of its net
// normal force would fail every vertex.
TEST(Certificate, ClothSqueezedBetweenTwoBodiesIsCheckedAgainstEachBodysCone) {
  constexpr double side = 0.1, offset = 1e-3, density = 0.2, mu = 0.3;
  TriangleMesh mesh = mesh::rectangle(side, side, 4, 4);
  for (auto& p : mesh.positions)
    p.z() = 0.5 * offset;
  ClothProblem problem(PETSC_COMM_WORLD, mesh, fabric(3000.0, 1e-5, density), {});
  problem.loads.gravity = {gravity, 0.0, 0.0};
  problem.contact.offset = offset;
  for (const auto& [name, z, up] :
       {std::tuple{"below", 0.0, 1.0}, std::tuple{"above", offset, -1.0}}) {
    contact::Body plate(name,
                        std::make_shared<contact::Plane>(Eigen::Vector3d(0.0, 0.0, z),
                                                         Eigen::Vector3d(0.0, 0.0, up)),
                        Eigen::Vector3d::Zero());
    plate.friction = {mu, mu};
    problem.bodies.push_back(plate);
  }
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, options, &report), 0);
  ASSERT_TRUE(report.converged) << report.reason;
  Certificate c;
  ASSERT_EQ(certify(problem, x, {}, &c), 0);
  VecDestroy(&x);
  const double weight = density * side * side * gravity;
  EXPECT_NEAR(c.reference_force, weight, 1e-9 * weight);
  EXPECT_LT(c.relative_residual, 1e-6);
  // Every vertex against each plate: two contacts per vertex, all sticking.
  EXPECT_EQ(c.coulomb.contacts, 2 * long(mesh.vertex_count()));
  EXPECT_EQ(c.coulomb.sticking, c.coulomb.contacts);
  EXPECT_TRUE(c.coulomb.passed()) << "worst |f_t| / mu_s f_n " << c.coulomb.worst_ratio;
  EXPECT_LT(c.coulomb.worst_ratio, 1.0);
  EXPECT_TRUE(c.certified()) << c.verdict();
}

TEST(Certificate, StatePushedIntoTheBodyFailsTheDepthCheck) {
  SheetOnSphere sheet;
  sheet.solve();
  // 3 mm down: the vertices on the pole end 2 mm inside the sphere.
  std::vector<Eigen::Vector3d> positions;
  ASSERT_EQ(sheet.problem->positions_everywhere(sheet.x, &positions), 0);
  for (auto& p : positions)
    p.z() -= 3e-3;
  ASSERT_EQ(sheet.problem->set_solution(positions, sheet.x), 0);
  CertificateOptions options;
  options.stability = false;
  Certificate c;
  ASSERT_EQ(certify(*sheet.problem, sheet.x, options, &c), 0);
  const double lowest = sheet.min_distance();
  ASSERT_LT(lowest, -1.5e-3);
  EXPECT_NEAR(c.relative_depth, (SheetOnSphere::offset - lowest) / SheetOnSphere::offset, 1e-9);
  EXPECT_FALSE(c.outside_bodies());
  EXPECT_GT(c.edges_inside, 0);
  EXPECT_FALSE(c.certified());
}

// A 10 cm square of two triangles standing in the x-z plane across a 2 mm
// thick horizontal plate: its two vertical sides and its diagonal cross the
// plate, both ends outside; the top and bottom edges stay clear.
TEST(Certificate, EdgesThroughAThinBodyAreCounted) {
  TriangleMesh mesh = mesh::rectangle(0.1, 0.1, 1, 1);
  for (auto& p : mesh.positions)
    p = Eigen::Vector3d(p.x(), 0.0, p.y() - 0.05);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, fabric(3000.0, 1e-5, 0.2), {});
  problem.contact.offset = 1e-4;
  const double thickness = 2e-3;
  problem.bodies.emplace_back(
      "plate",
      std::make_shared<contact::Box>(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, thickness)),
      Eigen::Vector3d::Zero());
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  CertificateOptions options;
  options.stability = false;
  Certificate c;
  ASSERT_EQ(certify(problem, x, options, &c), 0);
  EXPECT_EQ(c.edges, 5);
  EXPECT_EQ(c.edges_inside, 3);
  EXPECT_EQ(c.edges_through, 3);
  EXPECT_GT(c.min_distance, 0.0); // the vertices are all clear
  // The march reaches within a few tenths of the offset of the mid-plane.
  EXPECT_LT(c.deepest_edge_point, -0.5 * thickness + 0.5e-3);
  EXPECT_GE(c.deepest_edge_point, -0.5 * thickness - 1e-12);
  EXPECT_FALSE(c.certified());
  const nlohmann::json json = certificate_json(c);
  EXPECT_EQ(json["edges"]["inside_a_body"], 3);
  EXPECT_EQ(json["certified"], false);
  VecDestroy(&x);
}

// A checkpoint keeps certificates as their summary.json block: every
// measure and tolerance it holds reads back exactly, so the verdict does.
TEST(Certificate, JsonRoundTripKeepsEveryMeasure) {
  Certificate c;
  c.residual_norm = 0.1 / 3.0;
  c.reference_force = 1.4245;
  c.relative_residual = c.residual_norm / c.reference_force;
  c.options.residual_tolerance = 5e-2;
  c.seam_gap = 2.5e-4;
  c.options.seam_gap_tolerance = 1e-3;
  c.has_bodies = true;
  c.contact_offset = 1e-3;
  c.min_distance = 3.0e-4;
  c.relative_depth = 0.7;
  c.deepest_vertex = 17;
  c.options.depth_tolerance = 0.9;
  c.edges = 1200;
  c.edges_inside = 0;
  c.edges_through = 0;
  c.deepest_edge_point = 0.0;
  c.coulomb = {40, 30, 9, 1, 0, 1.07, 5};
  c.options.cone_tolerance = 0.05;
  c.placement.applicable = true;
  c.placement.carried_share = {0.75, 0.125};
  c.placement.pins_share = 0.125;
  c.placement.centroid_drop = 0.02;
  c.stability = {true, false, 900, 2, 1, 1e-3};
  const Certificate read = certificate_from_json(certificate_json(c));
  EXPECT_EQ(read.verdict(), c.verdict());
  EXPECT_EQ(certificate_json(read), certificate_json(c));
  EXPECT_EQ(read.relative_residual, c.relative_residual);
  EXPECT_EQ(read.placement.carried_share, c.placement.carried_share);
  EXPECT_EQ(read.stability.negative, 2);
  EXPECT_TRUE(read.saddle());
  c.has_bodies = false; // and so no contacts
  c.coulomb = {};
  c.placement.applicable = false;
  c.stability = {};
  const Certificate bare = certificate_from_json(certificate_json(c));
  EXPECT_FALSE(bare.has_bodies);
  EXPECT_FALSE(bare.placement.applicable);
  EXPECT_EQ(certificate_json(bare), certificate_json(c));
  EXPECT_THROW(certificate_from_json(nlohmann::json{{"certified", true}}),
               nlohmann::json::exception);
}

// A strip of length L, width w, its short edges pinned, compressed
// uniformly by strain e (an equilibrium without gravity): membrane force
// N = E e per unit width. Euler's load per unit width lies between
// pi^2 D / L^2 (pinned ends) and 4 pi^2 D / L^2 (clamped ends), D the
// bending stiffness: the strip buckles, and the compressed state is a
// saddle, when N is above it, and is stable when N is below.
Certificate compressed_strip(double bending) {
  const double length = 0.5, strain = 1e-3;
  TriangleMesh mesh = mesh::rectangle(length, 0.05, 20, 2);
  for (auto& p : mesh.positions)
    p.x() *= 1.0 - strain;
  const std::vector<int> ends =
      vertices_where(mesh, [](const Eigen::Vector3d& p) { return p.x() < 1e-9 || p.x() > 0.49; });
  ClothProblem problem(PETSC_COMM_WORLD, mesh, fabric(30000.0, bending, 0.2), ends);
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  Certificate c;
  EXPECT_EQ(certify(problem, x, {}, &c), 0);
  VecDestroy(&x);
  return c;
}

double euler_bending_for(double force_per_width, double end_factor, double length) {
  return force_per_width * length * length / (end_factor * M_PI * M_PI);
}

TEST(Certificate, StripCompressedAboveEulersLoadIsASaddle) {
  const double force = 30000.0 * 1e-3; // N/m
  // Clamped Euler load a quarter of the force.
  const Certificate c = compressed_strip(euler_bending_for(0.25 * force, 4.0, 0.5));
  EXPECT_LT(c.relative_residual, 1e-6); // uniform compression is an equilibrium
  ASSERT_TRUE(c.stability.assessed);
  EXPECT_GE(c.stability.negative, 1);
  EXPECT_TRUE(c.saddle());
  EXPECT_NE(c.verdict().find("saddle"), std::string::npos);
  EXPECT_FALSE(c.certified());
}

TEST(Certificate, StripCompressedBelowEulersLoadIsStable) {
  const double force = 30000.0 * 1e-3;
  // Pinned-ends Euler load four times the force.
  const Certificate c = compressed_strip(euler_bending_for(4.0 * force, 1.0, 0.5));
  ASSERT_TRUE(c.stability.assessed);
  EXPECT_EQ(c.stability.negative, 0);
  EXPECT_EQ(c.stability.zero_modes, 0);
}

// A 1 m square membrane without bending, its boundary pinned on a square
// stretched by 1 %: tension T = E 0.01, and its lowest out-of-plane mode has
// omega^2 = 2 pi^2 T / rho, far above the zero-mode shift: no negative
// direction, no zero mode.
TEST(Certificate, StretchedMembraneHasNoNegativeDirection) {
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 8, 8);
  std::vector<int> boundary = vertices_where(mesh, [](const Eigen::Vector3d& p) {
    return p.x() < 1e-9 || p.y() < 1e-9 || p.x() > 1.0 - 1e-9 || p.y() > 1.0 - 1e-9;
  });
  for (auto& p : mesh.positions)
    p *= 1.01;
  ClothProblem problem(PETSC_COMM_WORLD, mesh, fabric(30000.0, 0.0, 0.2), boundary);
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  Certificate c;
  ASSERT_EQ(certify(problem, x, {}, &c), 0);
  const double lowest = 2.0 * M_PI * M_PI * 30000.0 * 0.01 / 0.2;
  ASSERT_GT(lowest, 1e6 * c.stability.sigma);
  ASSERT_TRUE(c.stability.assessed);
  EXPECT_EQ(c.stability.free_dofs, 3 * 7 * 7);
  EXPECT_EQ(c.stability.negative, 0);
  EXPECT_EQ(c.stability.zero_modes, 0);
  EXPECT_TRUE(c.certified()) << c.verdict();
  VecDestroy(&x);
}

// A free, unstressed sheet with bending and no load: its six rigid-body
// motions are zero-energy modes, reported as such, not as negative.
TEST(Certificate, FreeSheetReportsSixZeroModes) {
  const TriangleMesh mesh = mesh::rectangle(0.3, 0.3, 6, 6);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, fabric(30000.0, 1e-3, 0.2), {});
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  Certificate c;
  ASSERT_EQ(certify(problem, x, {}, &c), 0);
  ASSERT_TRUE(c.stability.assessed);
  EXPECT_EQ(c.stability.negative, 0);
  EXPECT_EQ(c.stability.zero_modes, 6);
  VecDestroy(&x);
}

} // namespace
} // namespace sartor
