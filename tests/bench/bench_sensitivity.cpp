// Design sensitivity benchmark: a 0.5 m sheet hanging from its top edge, or
// held at its centre over a ball (-ball R, m; 0, the default: hanging)
// (n x n cells, Baraff-Witkin membrane, discrete-shell bending), its hem
// flared by an outline edit (the two lower corners pulled out and down,
// symmetrically, the interior following by mean value coordinates). Per
// mesh size and edit size it prints the CPU seconds of: the drape from
// scratch (the flat sheet), the sensitivity (factorisation and one dX), the
// re-solve from the linear prediction x + S dX and from the unchanged drape;
// and the distances of the prediction and of the unchanged drape from the
// re-solved equilibrium. It measures and prints, it never fails on time.
//
// Run: build/tests/bench/sartor-bench-sensitivity [-ball 0,1] [-sizes 20,40] [-edits 0.01,0.05]
// (edits: metres the hem corners move out, 0.4 of it down)
// (times are CPU seconds of this process: run it alone on one rank).

#include "contact/analytic_shapes.hpp"
#include "garment/pattern_edit.hpp"
#include "material/tension_curve.hpp"
#include "mesh/generators.hpp"
#include "solvers/sensitivity.hpp"
#include "solvers/statics.hpp"

#include <petscsys.h>

#include <cstdio>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace sartor;

double cpu_seconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

std::vector<double> numbers(const char* option, const std::string& fallback) {
  char text[256] = {0};
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, option, text, sizeof(text), &set);
  std::stringstream list(set ? std::string(text) : fallback);
  std::vector<double> values;
  for (std::string item; std::getline(list, item, ',');)
    values.push_back(std::stod(item));
  return values;
}

// The sheet; on a ball of radius `ball` (m) under its centre when > 0.
ProblemFactory sheet_factory(const std::vector<int>& pins, double ball) {
  return [pins, ball](MPI_Comm comm, const TriangleMesh& mesh, double floor) {
    ClothMaterial m(
        {TensionCurve::linear(1000.0, "bench"), TensionCurve::linear(1000.0, "bench"), 100.0, 0.0});
    m.bending_model = element::BendingModel::discrete_shell;
    m.bending_stiffness = std::max(1e-5, floor);
    m.areal_density = 0.2;
    auto problem = std::make_unique<ClothProblem>(comm, mesh, m, pins);
    problem->loads.gravity = {0.0, 0.0, -9.80665};
    if (ball > 0.0) {
      problem->bodies.emplace_back("ball",
                                   std::make_shared<contact::Sphere>(Eigen::Vector3d::Zero(), ball),
                                   Eigen::Vector3d::Zero());
    }
    return problem;
  };
}

struct Solved {
  std::unique_ptr<TriangleMesh> mesh;
  std::unique_ptr<ClothProblem> problem;
  Vec x = nullptr;
  double seconds = 0.0;
  int newton = 0;
  ~Solved() { VecDestroy(&x); }
};

// The drape of `mesh` from `start` (a state of `from`) or the flat sheet.
void drape(const ProblemFactory& factory, const TriangleMesh& mesh, ClothProblem* from, Vec start,
           Solved* solved) {
  solved->mesh = std::make_unique<TriangleMesh>(mesh);
  solved->problem = factory(PETSC_COMM_WORLD, *solved->mesh, 0.0);
  solved->problem->create_solution(&solved->x);
  if (start) transfer_vector(*from, start, *solved->problem, solved->x);
  StaticOptions options;
  options.minimise = true;
  StaticReport report;
  const double begin = cpu_seconds();
  solve_static(*solved->problem, solved->x, options, &report);
  solved->seconds = cpu_seconds() - begin;
  solved->newton = int(report.newton_iterations);
  if (!report.converged) std::printf("  (not converged: %s)\n", report.reason.c_str());
}

double distance(ClothProblem& a, Vec x, ClothProblem& b, Vec y) {
  Vec z = nullptr;
  VecDuplicate(x, &z);
  transfer_vector(b, y, a, z);
  VecAXPY(z, -1.0, x);
  PetscReal norm = 0.0;
  VecNorm(z, NORM_2, &norm);
  VecDestroy(&z);
  return norm;
}

// The hanging sheet, or (ball > 0) the sheet laid flat on the ball, held at
// its centre (the vertices within 3 cm), draping over it.
TriangleMesh sheet(int n, double ball, std::vector<int>* pins) {
  TriangleMesh mesh = mesh::rectangle(0.5, 0.5, n, n);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d p = mesh.positions[v];
    if (ball > 0.0) {
      mesh.positions[v] = Eigen::Vector3d(p.x() - 0.25, p.y() - 0.25, ball + 2e-3);
      if (mesh.positions[v].head<2>().norm() < 0.03) pins->push_back(int(v));
    } else {
      mesh.positions[v] = Eigen::Vector3d(p.x(), 0.0, p.y());
      if (p.y() == 0.5) pins->push_back(int(v));
    }
  }
  return mesh;
}

void run(int n, double ball, const std::vector<double>& edits) {
  std::vector<int> pins;
  const TriangleMesh mesh = sheet(n, ball, &pins);
  const ProblemFactory factory = sheet_factory(pins, ball);
  Solved base;
  drape(factory, mesh, nullptr, nullptr, &base);
  const std::vector<Eigen::Vector2d> outline = {
      Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(0.5, 0.5),
      Eigen::Vector2d(0.0, 0.5)};
  const std::vector<Eigen::Vector2d> corners =
      garment::symmetric_edit({Eigen::Vector2d(-1.0, -0.4), Eigen::Vector2d::Zero(),
                               Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
                              {1, -1, -1, -1}, Eigen::Vector2d(0.0, 1.0));
  RestChange change(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      change[t][k] = garment::outline_edit(outline, corners, {mesh.material_uv[t][k]}).front();

  double begin = cpu_seconds();
  DesignSensitivity sensitivity(*base.problem, base.x, factory);
  Vec slope = nullptr, predicted = nullptr;
  VecDuplicate(base.x, &slope);
  VecDuplicate(base.x, &predicted);
  sensitivity.apply(change, slope);
  const double sensitivity_seconds = cpu_seconds() - begin;
  std::printf(
      "%s, n %d, %zu triangles: drape from scratch %.3f s (%d Newton), sensitivity %.3f s\n",
      ball > 0.0 ? "on the ball" : "hanging", n, mesh.triangle_count(), base.seconds, base.newton,
      sensitivity_seconds);
  for (const double edit : edits) {
    VecWAXPY(predicted, edit, slope, base.x);
    const TriangleMesh edited = moved_rest(mesh, change, edit);
    Solved scratch, warm, unchanged;
    drape(factory, edited, nullptr, nullptr, &scratch);
    drape(factory, edited, base.problem.get(), predicted, &warm);
    drape(factory, edited, base.problem.get(), base.x, &unchanged);
    std::printf(
        "  edit %.3f m: from scratch %.3f s (%d), from the prediction %.3f s (%d), from the "
        "unchanged drape %.3f s (%d); distance to the re-solved drape: prediction %.3e m, "
        "unchanged %.3e m\n",
        edit, scratch.seconds, scratch.newton, warm.seconds, warm.newton, unchanged.seconds,
        unchanged.newton, distance(*base.problem, predicted, *warm.problem, warm.x),
        distance(*base.problem, base.x, *warm.problem, warm.x));
  }
  VecDestroy(&slope);
  VecDestroy(&predicted);
}

} // namespace

int main(int argc, char** argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  for (const double ball : numbers("-ball", "0"))
    for (const double n : numbers("-sizes", "20,40"))
      run(int(n), ball, numbers("-edits", "0.01,0.05"));
  return PetscFinalize() ? 1 : 0;
}
