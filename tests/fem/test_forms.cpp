// The discrete problem as a sum of energy forms (fem/form.hpp): every form's
// gradient against central differences of its energy and its exact Hessian
// against central differences of its gradient, each form alone; the exact
// rest-coordinate derivatives against central differences of problems
// rebuilt on moved patterns; the sum of
// the forms' residuals is the problem's; a toy form added in one file
// (spring_to_point_form.hpp) holds a free sheet where its springs pull it.

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/forms/inertia_form.hpp"
#include "mesh/generators.hpp"
#include "mesh/panels.hpp"
#include "solvers/sensitivity.hpp"
#include "solvers/statics.hpp"
#include "tests/fem/jacobian_check.hpp"
#include "tests/fem/spring_to_point_form.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace sartor {
namespace {

ClothMaterial cotton(element::BendingModel model) {
  ClothMaterial m(
      {TensionCurve::linear(65200, "test"), TensionCurve::linear(28200, "test"), 4288.0, 0.0});
  m.bending_model = model;
  m.bending_stiffness = 1e-3;
  m.areal_density = 0.2;
  return m;
}

// A jittered sheet 0.4 x 0.3 m near the top of a ball (its vertices around
// the middle within the contact offset), with every kind of form: membrane
// with creep strains, gravity, bending, a point force, contact with edge
// samples and friction anchors, a seam and springs to points.
struct Scene {
  TriangleMesh mesh;
  std::unique_ptr<ClothProblem> problem;
};

// A ball (friction 0.4) whose top is 0.5 mm below the middle of a 0.4 x
// 0.3 m sheet in z = 0: the middle vertices and edge samples (every 2 cm)
// lie in the 3 mm offset layer.
void put_on_ball(ClothProblem& p) {
  const Eigen::Vector3d middle(0.2, 0.15, 0.0);
  const double radius = 0.5;
  contact::Body ball(
      "ball",
      std::make_shared<contact::Sphere>(middle - Eigen::Vector3d(0, 0, radius + 0.0005), radius),
      Eigen::Vector3d::Zero());
  ball.friction.static_coefficient = ball.friction.kinetic_coefficient = 0.4;
  p.bodies.push_back(ball);
  p.contact.offset = 3e-3;
  p.contact.edge_sample_spacing = 0.02;
}

Scene scene(element::BendingModel model) {
  Scene s;
  s.mesh = mesh::rectangle(0.4, 0.3, 6, 5, mesh::RectanglePattern::perturbed);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (auto& p : s.mesh.positions)
    p += Eigen::Vector3d(jitter(random), jitter(random), jitter(random));
  s.problem =
      std::make_unique<ClothProblem>(PETSC_COMM_WORLD, s.mesh, cotton(model), std::vector<int>{0});
  ClothProblem& p = *s.problem;
  p.loads.gravity = {0, 0, -9.81};
  p.loads.point_forces = {{9, {0.1, -0.2, 0.3}}};
  p.nonelastic.assign(s.mesh.triangle_count(), {0.01, 0.02});
  put_on_ball(p);
  SeamSpring seam;
  seam.vertices = {{1, 40, -1}};
  seam.stiffness = 50.0;
  seam.length = 0.05;
  p.set_seams({seam});
  const int last = int(s.mesh.vertex_count()) - 1;
  p.add_form(std::make_unique<testing::SpringToPointForm>(
      p, std::vector<testing::SpringToPointForm::Spring>{{last, {0.5, 0.4, 0.1}}}, 30.0));
  return s;
}

double directional_energy_error(ClothProblem& problem, Vec x, Vec v, double h) {
  Vec g = nullptr, shifted = nullptr;
  VecDuplicate(x, &g);
  VecDuplicate(x, &shifted);
  ClothEnergy up, down;
  EXPECT_EQ(problem.residual(x, g), 0);
  VecWAXPY(shifted, h, v, x);
  EXPECT_EQ(problem.energy(shifted, &up), 0);
  VecWAXPY(shifted, -h, v, x);
  EXPECT_EQ(problem.energy(shifted, &down), 0);
  PetscScalar slope = 0.0;
  VecDot(g, v, &slope);
  VecDestroy(&g);
  VecDestroy(&shifted);
  const double difference = (up.total() - down.total()) / (2.0 * h);
  EXPECT_NE(slope, 0.0) << "the form does nothing here";
  return std::abs(difference - slope) / std::abs(slope);
}

Vec random_direction(Vec x) {
  Vec v = nullptr;
  VecDuplicate(x, &v);
  PetscRandom generator = nullptr;
  PetscRandomCreate(PETSC_COMM_WORLD, &generator);
  PetscRandomSetSeed(generator, 11);
  PetscRandomSeed(generator);
  VecSetRandom(v, generator);
  PetscRandomDestroy(&generator);
  return v;
}

TEST(Forms, EachFormsGradientAndHessianMatchDifferences) {
  for (auto model : {element::BendingModel::discrete_shell, element::BendingModel::patch}) {
    Scene s = scene(model);
    ClothProblem& problem = *s.problem;
    Vec x = nullptr;
    ASSERT_EQ(problem.create_solution(&x), 0);
    ASSERT_EQ(problem.update_contact(x), 0); // anchors where the sheet touches
    Vec v = random_direction(x);
    problem.exact_hessian = true;
    const std::vector<std::string> names = problem.form_names();
    for (const std::string& name : names) {
      // Active only in a coupled creep step: CreepMonolithic checks it there.
      if (name == "creep coupling") continue;
      for (const std::string& other : names)
        problem.enable_form(other, other == name);
      EXPECT_LT(directional_energy_error(problem, x, v, 1e-6), 1e-6) << name;
      // Gravity and point forces do not depend on the positions: J v and
      // the differences of the gradient are both exactly zero.
      const bool constant = name == "surface loads" || name == "point loads";
      const double error = testing::directional_jacobian_error(problem, x, v, 1e-6, NORM_2);
      if (!constant) {
        EXPECT_GE(error, 0.0) << name << ": assembly failed";
        EXPECT_LT(error, 1e-6) << name;
      } else {
        EXPECT_TRUE(std::isnan(error)) << name << ": 0/0 expected, got " << error;
      }
    }
    // Follower pressure (no potential): its Hessian alone.
    problem.loads.pressure = 5.0;
    for (const std::string& name : names)
      problem.enable_form(name, name == "surface loads");
    EXPECT_FALSE(problem.has_potential());
    EXPECT_LT(testing::directional_jacobian_error(problem, x, v, 1e-6, NORM_2), 1e-6);
    VecDestroy(&x);
    VecDestroy(&v);
  }
}

// A time step's inertia and damping (fem/forms/inertia_form.hpp): its
// gradient against central differences of its energy, its Hessian against
// differences of its gradient, and nothing at zero weights; ClothProblem
// refuses a form that says it is a time step's inertia.
TEST(Forms, InertiaFormsGradientAndHessianMatchDifferences) {
  Scene s = scene(element::BendingModel::discrete_shell);
  ClothProblem& problem = *s.problem;
  Vec x = nullptr, mass = nullptr, g = nullptr, u = nullptr, shifted = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  for (Vec* w : {&mass, &g, &u, &shifted})
    VecDuplicate(x, w);
  ASSERT_EQ(problem.lumped_mass(mass), 0);
  fem::InertiaForm form(mass);
  form.inertia_weight = 400.0; // 1/s^2: a step of 50 ms
  form.damping_weight = 3.0;
  Vec v = random_direction(x);
  VecWAXPY(form.predicted(), 0.01, v, x);
  VecWAXPY(form.previous(), -0.02, v, x);
  VecPointwiseMult(u, v, v); // another direction
  VecShift(u, -0.3);
  const double h = 1e-6;
  double up = 0.0, down = 0.0;
  VecWAXPY(shifted, h, u, x);
  ASSERT_EQ(form.energy(shifted, &up), 0);
  VecWAXPY(shifted, -h, u, x);
  ASSERT_EQ(form.energy(shifted, &down), 0);
  VecSet(g, 0.0);
  ASSERT_EQ(form.add_gradient(x, g), 0);
  PetscScalar slope = 0.0;
  VecDot(g, u, &slope);
  ASSERT_NE(slope, 0.0);
  EXPECT_LT(std::abs((up - down) / (2.0 * h) - slope), 1e-6 * std::abs(slope));
  Mat J = nullptr;
  ASSERT_EQ(problem.create_jacobian(&J), 0);
  const double error = testing::directional_derivative_error(
      J, x, u, h, NORM_2,
      [&](Vec y, Vec f) {
        VecSet(f, 0.0);
        return form.add_gradient(y, f);
      },
      [&](Vec y, Mat A) {
        MatZeroEntries(A);
        return form.add_hessian(y, false, A);
      });
  EXPECT_GE(error, 0.0) << "assembly failed";
  EXPECT_LT(error, 1e-6);
  // Zero weights: no energy, no force.
  form.inertia_weight = form.damping_weight = 0.0;
  double none = 1.0;
  ASSERT_EQ(form.energy(x, &none), 0);
  EXPECT_EQ(none, 0.0);
  VecSet(g, 0.0);
  ASSERT_EQ(form.add_gradient(x, g), 0);
  PetscReal force = 1.0;
  VecNorm(g, NORM_INFINITY, &force);
  EXPECT_EQ(force, 0.0);
  struct TimeStepTerm final : fem::Form {
    const char* name() const override { return "a time step's term"; }
    fem::EnergyPart part() const override { return fem::EnergyPart::inertia; }
    void add_energy(const fem::FormPoint&, double*) const override {}
    void add_gradient(const fem::FormPoint&, PetscScalar*) const override {}
  };
  EXPECT_THROW(problem.add_form(std::make_unique<TimeStepTerm>()), std::invalid_argument);
  MatDestroy(&J);
  for (Vec* w : {&x, &mass, &g, &u, &shifted, &v})
    VecDestroy(w);
}

// The volume under a piecewise-linear surface whose boundary lies in z = 0:
// each triangle's prism, its signed area in the xy plane times its mean
// height (an independent formula: the form sums tetrahedra on a centre).
double volume_under(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& x) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = x[std::size_t(t[0])], b = x[std::size_t(t[1])],
                          c = x[std::size_t(t[2])];
    const double area_xy = 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
    volume += area_xy * (a.z() + b.z() + c.z()) / 3.0;
  }
  return volume;
}

// Follower pressure on a sheet whose whole boundary is pinned is the
// gradient of -p times the enclosed volume (and has a potential only then):
// the energy is that volume's work, and its central differences are the
// problem's residual.
TEST(Forms, PressureOnAHeldBoundaryIsMinusPTimesTheVolume) {
  const TriangleMesh flat = mesh::rectangle(0.4, 0.3, 6, 5, mesh::RectanglePattern::perturbed);
  const std::vector<int> boundary = boundary_vertices(flat);
  ClothMaterial material = cotton(element::BendingModel::discrete_shell);
  material.areal_density = 0.0;
  ClothProblem problem(PETSC_COMM_WORLD, flat, material, boundary);
  const double pressure = 5.0;
  problem.loads.pressure = pressure;
  for (const std::string& name : problem.form_names())
    problem.enable_form(name, name == "surface loads");
  EXPECT_TRUE(problem.has_potential());
  // A bulge with the boundary in place, and sideways moves of the inside.
  std::vector<Eigen::Vector3d> bulged = flat.positions;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<bool> on_boundary(flat.vertex_count(), false);
  for (int v : boundary)
    on_boundary[std::size_t(v)] = true;
  for (std::size_t v = 0; v < bulged.size(); ++v) {
    if (on_boundary[v]) continue;
    const Eigen::Vector3d p = bulged[v];
    bulged[v] += Eigen::Vector3d(jitter(random), jitter(random),
                                 std::sin(M_PI * p.x() / 0.4) * std::sin(M_PI * p.y() / 0.3) *
                                     (0.05 + jitter(random)));
  }
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  ASSERT_EQ(problem.set_solution(bulged, x), 0);
  ClothEnergy energy;
  ASSERT_EQ(problem.energy(x, &energy), 0);
  const double work = pressure * volume_under(flat, bulged);
  EXPECT_GT(work, 0.0);
  EXPECT_NEAR(energy.external, -work, 1e-12 * work);
  Vec v = random_direction(x);
  EXPECT_LT(directional_energy_error(problem, x, v, 1e-6), 1e-7);
  VecDestroy(&x);
  VecDestroy(&v);
  // One boundary vertex let go: the loads are no gradient any more.
  ClothProblem loose(PETSC_COMM_WORLD, flat, material,
                     std::vector<int>(boundary.begin() + 1, boundary.end()));
  loose.loads.pressure = pressure;
  EXPECT_FALSE(loose.has_potential());
}

// Newton systems go to MUMPS's LDL^T (its upper triangle only) exactly when
// the Jacobian is symmetric: a potential, and no releasable pin whose rows
// are replaced (they are not symmetric).
TEST(Forms, TheJacobianIsSymmetricForAPotentialWithoutReleasablePins) {
  const TriangleMesh flat = mesh::rectangle(0.4, 0.3, 4, 3, mesh::RectanglePattern::perturbed);
  const ClothMaterial material = cotton(element::BendingModel::discrete_shell);
  ClothProblem fixed(PETSC_COMM_WORLD, flat, material, {0, 1});
  EXPECT_TRUE(fixed.symmetric_jacobian());
  fixed.loads.pressure = 5.0; // on a free edge: no potential
  EXPECT_FALSE(fixed.symmetric_jacobian());
  const double never = std::numeric_limits<double>::infinity();
  const std::vector<ClothMaterial> materials{material};
  ClothProblem kept(PETSC_COMM_WORLD, flat, materials, {0, 1}, {never, never});
  EXPECT_TRUE(kept.symmetric_jacobian());
  ClothProblem released(PETSC_COMM_WORLD, flat, materials, {0, 1}, {0.5, never});
  EXPECT_TRUE(released.has_potential());
  EXPECT_FALSE(released.symmetric_jacobian());
}

TEST(Forms, TheProblemsResidualIsTheSumOfItsForms) {
  Scene s = scene(element::BendingModel::discrete_shell);
  ClothProblem& problem = *s.problem;
  // The creep coupling stands in for the membrane in a coupled creep step
  // only: inactive here, it adds nothing.
  const std::vector<std::string> expected = {"membrane",        "creep coupling", "surface loads",
                                             "hinge bending",   "point loads",    "contact",
                                             "spring to point", "seams"};
  EXPECT_EQ(problem.form_names(), expected);
  Vec x = nullptr, total = nullptr, sum = nullptr, one = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  ASSERT_EQ(problem.update_contact(x), 0);
  for (Vec* w : {&total, &sum, &one})
    VecDuplicate(x, w);
  ASSERT_EQ(problem.residual(x, total), 0);
  VecSet(sum, 0.0);
  for (const std::string& name : expected) {
    for (const std::string& other : expected)
      problem.enable_form(other, other == name);
    ASSERT_EQ(problem.residual(x, one), 0);
    VecAXPY(sum, 1.0, one);
  }
  PetscReal scale = 0.0, difference = 0.0;
  VecNorm(total, NORM_INFINITY, &scale);
  VecAXPY(sum, -1.0, total);
  VecNorm(sum, NORM_INFINITY, &difference);
  EXPECT_LT(difference, 1e-12 * scale);
  EXPECT_THROW(problem.enable_form("gravity", false), InputError);
  for (Vec* w : {&x, &total, &sum, &one})
    VecDestroy(w);
}

// The problem's exact rest derivative at x against central differences (step
// h) of the residuals of problems `build` makes on the pattern moved by
// +-h change, in the base problem's layout; with `share_state`, the rebuilt
// problems take the base's state (friction anchors). Returns the norms of
// the derivative and of its error.
struct RestDerivativeCheck {
  double size = 0.0, error = 0.0;
};
template <class Build>
RestDerivativeCheck check_rest_derivative(ClothProblem& base, const Build& build,
                                          const TriangleMesh& mesh, const RestChange& change, Vec x,
                                          bool share_state) {
  const double h = 1e-4; // times a change of up to 1 cm: 1 micrometre
  Vec exact = nullptr, difference = nullptr, side = nullptr;
  for (Vec* w : {&exact, &difference, &side})
    VecDuplicate(x, w);
  EXPECT_EQ(base.rest_derivative(x, change, exact), 0);
  VecSet(difference, 0.0);
  for (const double s : {h, -h}) {
    const TriangleMesh moved = moved_rest(mesh, change, s); // the problem keeps a reference
    auto other = build(moved);
    if (share_state) {
      EXPECT_EQ(copy_problem_state(base, *other), 0);
    }
    Vec y = nullptr, f = nullptr;
    EXPECT_EQ(other->create_solution(&y), 0);
    VecDuplicate(y, &f);
    EXPECT_EQ(transfer_vector(base, x, *other, y), 0);
    EXPECT_EQ(other->residual(y, f), 0);
    EXPECT_EQ(transfer_vector(*other, f, base, side), 0);
    VecAXPY(difference, s > 0 ? 0.5 / h : -0.5 / h, side);
    VecDestroy(&y);
    VecDestroy(&f);
  }
  RestDerivativeCheck check;
  VecNorm(exact, NORM_2, &check.size);
  VecAXPY(difference, -1.0, exact);
  VecNorm(difference, NORM_2, &check.error);
  for (Vec* w : {&exact, &difference, &side})
    VecDestroy(w);
  return check;
}

TEST(Forms, RestDerivativesMatchDifferencesOfRebuiltProblems) {
  TriangleMesh mesh = mesh::rectangle(0.4, 0.3, 6, 5, mesh::RectanglePattern::perturbed);
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (auto& p : mesh.positions)
    p += Eigen::Vector3d(jitter(random), jitter(random), jitter(random));
  std::vector<Eigen::Vector2d> delta_uv(mesh.vertex_count());
  for (auto& d : delta_uv)
    d = {jitter(random), jitter(random)};
  const RestChange change = rest_change_per_vertex(mesh, delta_uv);
  // The patch model also with the first two rows clamped (triangles of
  // fixed vertices impose their plane's slopes on their neighbours).
  const std::vector<int> clamp = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13};
  const auto build = [](const TriangleMesh& m, const std::string& form,
                        const std::vector<int>& pins) {
    const auto model = form == "patch bending" ? element::BendingModel::patch
                                               : element::BendingModel::discrete_shell;
    auto problem = std::make_unique<ClothProblem>(PETSC_COMM_WORLD, m, cotton(model), pins);
    problem->loads.gravity = {0, 0, -9.81};
    problem->loads.point_forces = {{9, {0.1, -0.2, 0.3}}};
    problem->nonelastic.assign(m.triangle_count(), {0.01, 0.02});
    for (const std::string& name : problem->form_names())
      problem->enable_form(name, name == form);
    return problem;
  };
  // And with one interior vertex moved: a patch's rest data change with the
  // nodes two rings out (its neighbours' patches).
  std::vector<Eigen::Vector2d> one_vertex(mesh.vertex_count(), Eigen::Vector2d::Zero());
  one_vertex[24] = {0.01, -0.006};
  const RestChange vertex_change = rest_change_per_vertex(mesh, one_vertex);
  struct Case {
    std::string form;
    std::vector<int> pins;
    const RestChange& change;
  };
  const std::vector<Case> cases = {
      {"membrane", {0}, change},        {"surface loads", {0}, change},
      {"hinge bending", {0}, change},   {"patch bending", {0}, change},
      {"patch bending", clamp, change}, {"patch bending", {0}, vertex_change},
      {"point loads", {0}, change}};
  for (const auto& [form, pins, moved] : cases) {
    auto base = build(mesh, form, pins);
    Vec x = nullptr;
    ASSERT_EQ(base->create_solution(&x), 0);
    const auto rebuild = [&](const TriangleMesh& m) { return build(m, form, pins); };
    const RestDerivativeCheck check = check_rest_derivative(*base, rebuild, mesh, moved, x, false);
    if (form == "point loads") {
      EXPECT_EQ(check.size, 0.0) << form;
      EXPECT_LT(check.error, 1e-9) << form; // N: the forces do not depend on the pattern
    } else {
      EXPECT_GT(check.size, 0.0) << form << ", " << pins.size() << " pins";
      EXPECT_LT(check.error, 1e-6 * check.size) << form << ", " << pins.size() << " pins";
    }
    VecDestroy(&x);
  }
  // A form without a rest derivative (a user's) is refused, not left out.
  ClothProblem with_spring(PETSC_COMM_WORLD, mesh, cotton(element::BendingModel::patch), {0});
  with_spring.add_form(std::make_unique<testing::SpringToPointForm>(
      with_spring, std::vector<testing::SpringToPointForm::Spring>{{5, {0.1, 0.2, 0.3}}}, 30.0));
  Vec x = nullptr, derivative = nullptr;
  ASSERT_EQ(with_spring.create_solution(&x), 0);
  VecDuplicate(x, &derivative);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_NE(with_spring.rest_derivative(x, change, derivative), 0);
  PetscPopErrorHandler();
  VecDestroy(&x);
  VecDestroy(&derivative);
}

// The contact form's rest derivative (through the automatic penalty
// stiffness: vertex areas and the longest edge) against central differences
// of problems rebuilt on moved patterns that share the friction anchors: a
// jittered sheet on a ball, its vertices and edge samples in the offset
// layer, moved 1 mm off the anchors so that the springs pull.
TEST(Forms, ContactRestDerivativeMatchesDifferencesOfRebuiltProblems) {
  TriangleMesh mesh = mesh::rectangle(0.4, 0.3, 6, 5, mesh::RectanglePattern::perturbed);
  std::mt19937_64 random(9);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (auto& p : mesh.positions)
    p += Eigen::Vector3d(jitter(random), jitter(random), 0.25 * jitter(random));
  std::vector<Eigen::Vector2d> delta_uv(mesh.vertex_count());
  for (auto& d : delta_uv)
    d = {2.5 * jitter(random), 2.5 * jitter(random)};
  const RestChange change = rest_change_per_vertex(mesh, delta_uv);
  const auto build = [](const TriangleMesh& m) {
    auto problem = std::make_unique<ClothProblem>(
        PETSC_COMM_WORLD, m, cotton(element::BendingModel::discrete_shell), std::vector<int>{0});
    put_on_ball(*problem);
    for (const std::string& name : problem->form_names())
      problem->enable_form(name, name == "contact");
    return problem;
  };
  auto base = build(mesh);
  Vec x = nullptr;
  ASSERT_EQ(base->create_solution(&x), 0);
  ASSERT_EQ(base->update_contact(x), 0); // anchors where the sheet touches
  Vec shift = random_direction(x);
  VecShift(shift, -0.5); // entries in [-0.5, 0.5)
  VecAXPY(x, 2e-3, shift);
  const RestDerivativeCheck check = check_rest_derivative(*base, build, mesh, change, x, true);
  EXPECT_GT(check.size, 0.0);
  EXPECT_LT(check.error, 1e-6 * check.size);
  VecDestroy(&x);
  VecDestroy(&shift);
}

TEST(Forms, SeamRestDerivativeMatchesDifferencesOfRebuiltProblems) {
  mesh::PanelMesh tube = mesh::tube_panels(0.4, 0.3, 6, 5, 7, 4, 0.05);
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (auto& p : tube.mesh.positions)
    p += Eigen::Vector3d(jitter(random), jitter(random), jitter(random));
  std::vector<Eigen::Vector2d> delta_uv(tube.mesh.vertex_count());
  for (auto& d : delta_uv)
    d = {2.5 * jitter(random), 2.5 * jitter(random)};
  const RestChange change = rest_change_per_vertex(tube.mesh, delta_uv);
  SeamStiffness stiffness;
  stiffness.modulus = 65200.0;
  const auto build = [&](const TriangleMesh& m) {
    auto problem = std::make_unique<ClothProblem>(
        PETSC_COMM_WORLD, m, cotton(element::BendingModel::discrete_shell), std::vector<int>{0});
    problem->set_seams(tube.seams, stiffness);
    for (const std::string& name : problem->form_names())
      problem->enable_form(name, name == "seams");
    return problem;
  };
  auto base = build(tube.mesh);
  Vec x = nullptr, derivative = nullptr;
  ASSERT_EQ(base->create_solution(&x), 0);
  VecDuplicate(x, &derivative);
  const RestDerivativeCheck check =
      check_rest_derivative(*base, build, tube.mesh, change, x, false);
  EXPECT_GT(check.size, 0.0);
  EXPECT_LT(check.error, 1e-6 * check.size);
  // Given springs, and springs still being sewn, have none: refused.
  ClothProblem given(PETSC_COMM_WORLD, tube.mesh, cotton(element::BendingModel::discrete_shell),
                     std::vector<int>{0});
  given.set_seams(seam_springs(tube.mesh, tube.seams, stiffness));
  base->sewing_tension = 10.0;
  base->sewing_stage = 0.5;
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_NE(given.rest_derivative(x, change, derivative), 0);
  EXPECT_NE(base->rest_derivative(x, change, derivative), 0);
  PetscPopErrorHandler();
  VecDestroy(&x);
  VecDestroy(&derivative);
}

TEST(Forms, SpringsToPointsHoldAFreeSheetWhereTheyPullIt) {
  // No pins, no loads: three springs to the placement of three corners
  // moved by d carry the sheet there rigidly, unstrained.
  TriangleMesh mesh = mesh::rectangle(0.4, 0.3, 4, 3, mesh::RectanglePattern::perturbed);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, cotton(element::BendingModel::patch), {});
  const Eigen::Vector3d d(0.01, -0.02, 0.005);
  std::vector<testing::SpringToPointForm::Spring> springs;
  for (int v : {0, 4, int(mesh.vertex_count()) - 1})
    springs.push_back({v, mesh.positions[std::size_t(v)] + d});
  problem.add_form(std::make_unique<testing::SpringToPointForm>(problem, springs, 100.0));
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = 1;
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, options, &report), 0);
  EXPECT_TRUE(report.converged);
  std::vector<Eigen::Vector3d> positions;
  ASSERT_EQ(problem.gather_positions(x, &positions), 0);
  for (std::size_t v = 0; v < positions.size(); ++v)
    EXPECT_LT((positions[v] - mesh.positions[v] - d).norm(), 1e-9) << "vertex " << v;
  ClothEnergy energy;
  ASSERT_EQ(problem.energy(x, &energy), 0);
  EXPECT_LT(energy.membrane, 1e-12);
  VecDestroy(&x);
}

// Springs whose energy and force have stiffness k but whose Hessian claims
// `factor` times k: a Hessian far stiffer than the potential along the
// step, as the projected Hessian of unstable or compressed cloth is.
class OverstiffSprings final : public fem::Form {
public:
  OverstiffSprings(const ClothProblem& problem,
                   const std::vector<testing::SpringToPointForm::Spring>& springs, double k,
                   double factor)
      : true_(problem, springs, k), claimed_(problem, springs, factor * k) {}
  const char* name() const override { return "overstiff springs"; }
  fem::EnergyPart part() const override { return fem::EnergyPart::external; }
  void add_energy(const fem::FormPoint& at, double* sum) const override {
    true_.add_energy(at, sum);
  }
  void add_gradient(const fem::FormPoint& at, PetscScalar* f) const override {
    true_.add_gradient(at, f);
  }
  PetscErrorCode add_hessian(const fem::FormPoint& at, Mat J) const override {
    return claimed_.add_hessian(at, J);
  }

private:
  testing::SpringToPointForm true_, claimed_;
};

TEST(Forms, WholeStepsLengthenWhereTheHessianIsTooStiff) {
  // The sheet carried rigidly by a stiff spring at every vertex whose
  // Hessian is 1000 times too stiff: each whole Newton step goes 1/1000 of
  // the way and leaves |F| 0.999 of what it was, so without lengthening the
  // steps 50 Newton iterations end 5 % of the way. Doubled nine times (to
  // 0.512 of the way, where Phi's slope has fallen below half), then to the
  // secant's zero of the slope (the whole way: Phi is quadratic along the
  // step), the first step leaves 1e-7 of |F| (measured 4e-8).
  TriangleMesh mesh = mesh::rectangle(0.4, 0.3, 4, 3, mesh::RectanglePattern::perturbed);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, cotton(element::BendingModel::patch), {});
  const Eigen::Vector3d d(0.01, -0.02, 0.005);
  std::vector<testing::SpringToPointForm::Spring> springs;
  for (int v = 0; v < int(mesh.vertex_count()); ++v)
    springs.push_back({v, mesh.positions[std::size_t(v)] + d});
  problem.add_form(std::make_unique<OverstiffSprings>(problem, springs, 1e5, 1000.0));
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = 1;
  options.minimise = true; // at SNES's default -snes_max_it, 50
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, options, &report), 0);
  EXPECT_TRUE(report.minimised);
  EXPECT_TRUE(report.converged) << report.reason;
  EXPECT_GE(report.minimiser.extended_steps, 10);
  EXPECT_LE(report.newton_iterations, 20);
  std::printf("overstiff springs: %d Newton iterations, %d steps lengthened\n",
              int(report.newton_iterations), int(report.minimiser.extended_steps));
  std::vector<Eigen::Vector3d> positions;
  ASSERT_EQ(problem.gather_positions(x, &positions), 0);
  for (std::size_t v = 0; v < positions.size(); ++v)
    EXPECT_LT((positions[v] - mesh.positions[v] - d).norm(), 1e-8) << "vertex " << v;
  VecDestroy(&x);
}

} // namespace
} // namespace sartor
