// Creep in the structure (thesis §5.3, Algorithm 2): load histories, the
// creep strip under dead load against the material-point law of `sartor
// creep` for all ten Table 5.1 parameter sets on coarse and fine meshes, the
// same run on every rank count, and checkpoints that restore a run exactly.

#include "common/error.hpp"
#include "fem/checkpoint.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/creep_coupling.hpp"
#include "material/fabric.hpp"
#include "material/strip_creep.hpp"
#include "mesh/generators.hpp"
#include "solvers/creep_analysis.hpp"
#include "solvers/load_history.hpp"
#include "solvers/sensitivity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <random>

namespace sartor {
namespace {

bool root() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank == 0;
}

TEST(LoadHistory, InterpolatesAndJumps) {
  const LoadHistory history = LoadHistory::parse("0:1; 10:3; 10:0; 20:0", "test");
  EXPECT_DOUBLE_EQ(history.before(-1.0), 1.0);
  EXPECT_DOUBLE_EQ(history.after(5.0), 2.0);
  EXPECT_DOUBLE_EQ(history.before(10.0), 3.0);
  EXPECT_DOUBLE_EQ(history.after(10.0), 0.0);
  EXPECT_DOUBLE_EQ(history.after(30.0), 0.0);
  EXPECT_EQ(history.times(), (std::vector<double>{0.0, 10.0, 20.0}));
  EXPECT_DOUBLE_EQ(LoadHistory().before(7.0), 1.0);
}

TEST(LoadHistory, RejectsMalformedKnots) {
  const auto message = [](const std::string& text) {
    try {
      LoadHistory::parse(text, "option --load-history");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(message("0:1; 5:x").find("'5:x' is not TIME:FACTOR"), std::string::npos);
  EXPECT_NE(message("0:1; 5:2; 3:1").find("knot 3"), std::string::npos);
  EXPECT_NE(message("0:1; 5:2; 5:1; 5:0").find("more than two knots"), std::string::npos);
  EXPECT_NE(message("").find("no knot"), std::string::npos);
}

constexpr double strip_length = 0.15;   // m, along the loaded direction
constexpr double strip_width = 0.08;    // m
constexpr double strip_force = 196.133; // N: 20 kgf
constexpr double sample_interval = 300.0;

struct StripResult {
  std::map<double, double> strain; // output time -> elongation / length (rank 0)
  CreepReport report;
};

// The thesis' creep test on a strip whose long side runs along `along`: held
// on one short edge, the force spread over the other by consistent nodal
// loads, 1 h loaded, 1 h unloaded.
StripResult run_strip(MPI_Comm comm, const Fabric& fabric, Direction along, int cells_long,
                      int cells_wide) {
  const bool warp = along == Direction::warp;
  const int axis = warp ? 0 : 1;
  const TriangleMesh mesh =
      warp ? mesh::rectangle(strip_length, strip_width, cells_long, cells_wide)
           : mesh::rectangle(strip_width, strip_length, cells_wide, cells_long);
  ClothMaterial material(
      {fabric.in(Direction::warp).elastic, fabric.in(Direction::weft).elastic, 0.0, 0.0});
  material.membrane.shear_modulus = 0.1 * material.membrane.warp.initial_modulus();
  material.bending_stiffness = 1e-6;
  std::vector<int> pins, loaded;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double s = mesh.positions[v][axis];
    if (s == 0.0) pins.push_back(int(v));
    if (std::abs(s - strip_length) < 1e-12) loaded.push_back(int(v));
  }
  ClothProblem problem(comm, mesh, material, pins);
  const double spacing = strip_width / cells_wide;
  for (int v : loaded) {
    const double across = mesh.positions[std::size_t(v)][1 - axis];
    const bool corner = across < 1e-12 || std::abs(across - strip_width) < 1e-12;
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    force[axis] = strip_force / strip_width * spacing * (corner ? 0.5 : 1.0);
    problem.loads.point_forces.push_back({v, force});
  }
  CreepCoupling creep(
      problem, {CreepMaterial{fabric.in(Direction::warp).creep, fabric.in(Direction::weft).creep}});
  CreepOptions options;
  options.time_end = 7200.0;
  options.time_step = 1.0;
  options.creep_tolerance = 5e-3;
  options.load = LoadHistory::parse("0:1; 3600:1; 3600:0", "strip");
  options.output_interval = sample_interval;
  StripResult result;
  const CreepObserver record = [&](const CreepStepReport& step, Vec x) -> PetscErrorCode {
    std::vector<Eigen::Vector3d> positions;
    PetscFunctionBeginUser;
    if (!step.output) PetscFunctionReturn(0);
    PetscCall(problem.gather_positions(x, &positions));
    if (positions.empty()) PetscFunctionReturn(0);
    double mean = 0.0;
    for (int v : loaded)
      mean += positions[std::size_t(v)][axis] - strip_length;
    result.strain[step.time] = mean / double(loaded.size()) / strip_length;
    PetscFunctionReturn(0);
  };
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  EXPECT_EQ(solve_creep(problem, creep, x, options, &result.report, record), 0);
  EXPECT_EQ(VecDestroy(&x), 0);
  return result;
}

// The material-point response of `sartor creep` at the sample times (after
// a jump: its right side).
std::map<double, double> strip_reference(const DirectionalMaterial& material) {
  const TensionHistory history =
      TensionHistory::creep_recovery(strip_force / strip_width, 3600.0, 3600.0);
  std::map<double, double> strain;
  for (const StripState& s :
       simulate_strip(material, history, uniform_sample_times(history, sample_interval)))
    strain[s.time] = s.strain_total;
  return strain;
}

TEST(CreepStrip, FollowsTheMaterialLawForEveryTable51SetOnCoarseAndFineMeshes) {
  for (const FabricPreset& preset : fabric_presets()) {
    const Fabric fabric = preset_fabric(preset.name);
    for (Direction along : {Direction::warp, Direction::weft}) {
      const auto reference = strip_reference(fabric.in(along));
      for (const auto& [cells_long, cells_wide] : {std::pair{2, 1}, std::pair{8, 4}}) {
        SCOPED_TRACE(std::string(preset.name) + ":" + name_of(along) + " on " +
                     std::to_string(cells_long) + "x" + std::to_string(cells_wide));
        const StripResult run = run_strip(PETSC_COMM_WORLD, fabric, along, cells_long, cells_wide);
        ASSERT_TRUE(run.report.completed) << run.report.reason;
        if (!root()) continue;
        ASSERT_EQ(run.strain.size(), reference.size());
        double worst = 0.0;
        for (const auto& [time, strain] : run.strain) {
          ASSERT_EQ(reference.count(time), 1u) << "no reference at t = " << time;
          const double expected = reference.at(time);
          worst = std::max(worst, std::abs(strain - expected) / std::abs(expected));
        }
        EXPECT_LT(worst, 1e-6);
        // Loaded, the strip creeps beyond its immediate stretch; unloaded, it
        // keeps its permanent part.
        EXPECT_GT(run.strain.at(3600.0 - sample_interval), 1.01 * run.strain.at(0.0));
        EXPECT_GT(run.strain.at(7200.0), 0.0);
      }
    }
  }
}

// Every rank count gives the same history: a strip run on all ranks against
// the same run on this rank alone.
TEST(CreepStripMpi, SameOnEveryRankCount) {
  const Fabric fabric = preset_fabric("denim");
  const StripResult all = run_strip(PETSC_COMM_WORLD, fabric, Direction::weft, 8, 4);
  const StripResult alone = run_strip(PETSC_COMM_SELF, fabric, Direction::weft, 8, 4);
  if (!root()) return;
  ASSERT_EQ(all.strain.size(), alone.strain.size());
  for (const auto& [time, strain] : all.strain)
    EXPECT_NEAR(strain, alone.strain.at(time), 1e-12 * std::abs(strain)) << "t = " << time;
}

// The monolithic coupling's tangent: at a stretched, sheared and perturbed
// state, with a creep history behind it, J v against central differences of
// the residual, for both membrane models and while loading and recovering.
TEST(CreepMonolithic, TangentMatchesDifferencesOfTheResidual) {
  const TriangleMesh mesh = mesh::rectangle(0.15, 0.08, 3, 2);
  const Fabric fabric = preset_fabric("cotton_twill");
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.positions[v].x() == 0.0) pins.push_back(int(v));
  }
  std::mt19937 random(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto model :
       {element::MembraneModel::baraff_witkin, element::MembraneModel::saint_venant_kirchhoff}) {
    for (const double load_scale : {1.0, 0.2}) { // the tension rises, then falls
      SCOPED_TRACE(std::string(model == element::MembraneModel::baraff_witkin ? "BW" : "StVK") +
                   (load_scale < 1.0 ? ", recovering" : ", loading"));
      ClothMaterial material(
          {fabric.in(Direction::warp).elastic, fabric.in(Direction::weft).elastic, 300.0, 0.2});
      material.membrane_model = model;
      ClothProblem problem(PETSC_COMM_WORLD, mesh, material, pins);
      CreepCoupling creep(problem, {CreepMaterial{fabric.in(Direction::warp).creep,
                                                  fabric.in(Direction::weft).creep}});
      std::vector<Eigen::Vector3d> placed = mesh.positions;
      const auto place = [&](double stretch) {
        for (std::size_t v = 0; v < placed.size(); ++v) {
          const Eigen::Vector3d& p = mesh.positions[v];
          placed[v] = {p.x() * (1.0 + stretch),
                       p.y() * (1.0 + 0.3 * stretch) + 0.2 * stretch * p.x(), 0.01 * p.x() * p.y()};
          if (p.x() > 0.0)
            placed[v] += 2e-3 * Eigen::Vector3d(unit(random), unit(random), unit(random));
        }
      };
      Vec x = nullptr, v = nullptr, f = nullptr, plus = nullptr, minus = nullptr, jv = nullptr;
      Mat J = nullptr;
      ASSERT_EQ(problem.create_solution(&x), 0);
      for (Vec* w : {&v, &f, &plus, &minus, &jv})
        ASSERT_EQ(VecDuplicate(x, w), 0);
      ASSERT_EQ(problem.create_jacobian(&J), 0);
      // A creep history: 60 s at 8 % stretch, then the state of the check.
      place(0.08);
      ASSERT_EQ(problem.set_solution(placed, x), 0);
      ASSERT_EQ(creep.record_tensions(x), 0);
      double increment = 0.0;
      ASSERT_EQ(creep.advance(x, 60.0, &increment), 0);
      creep.commit();
      ASSERT_EQ(creep.record_tensions(x), 0);
      place(0.08 * load_scale);
      ASSERT_EQ(problem.set_solution(placed, x), 0);
      creep.couple(30.0);
      ASSERT_EQ(problem.jacobian(x, J), 0);
      ASSERT_EQ(VecSetRandom(v, nullptr), 0);
      ASSERT_EQ(MatMult(J, v, jv), 0);
      const double h = 1e-7;
      ASSERT_EQ(VecWAXPY(plus, h, v, x), 0);
      ASSERT_EQ(VecWAXPY(minus, -h, v, x), 0);
      ASSERT_EQ(problem.residual(plus, f), 0);
      ASSERT_EQ(problem.residual(minus, plus), 0);
      ASSERT_EQ(VecAXPY(f, -1.0, plus), 0);
      ASSERT_EQ(VecScale(f, 0.5 / h), 0);
      PetscReal exact = 0.0, difference = 0.0;
      ASSERT_EQ(VecNorm(jv, NORM_INFINITY, &exact), 0);
      ASSERT_EQ(VecAXPY(f, -1.0, jv), 0);
      ASSERT_EQ(VecNorm(f, NORM_INFINITY, &difference), 0);
      EXPECT_LT(difference, 1e-6 * exact);
      // Without the creep term the tangent is measurably wrong: the check
      // sees it.
      creep.uncouple();
      ASSERT_EQ(problem.jacobian(x, J), 0);
      ASSERT_EQ(MatMult(J, v, plus), 0);
      ASSERT_EQ(VecAXPY(plus, -1.0, jv), 0);
      ASSERT_EQ(VecNorm(plus, NORM_INFINITY, &difference), 0);
      EXPECT_GT(difference, 1e-4 * exact);
      MatDestroy(&J);
      for (Vec* w : {&x, &v, &f, &plus, &minus, &jv})
        VecDestroy(w);
    }
  }
}

TEST(CreepMonolithic, RestDerivativeMatchesDifferencesOfRebuiltProblems) {
  // A coupled step's residual on the pattern moved by +-h dX, each problem
  // rebuilt with the same committed creep state, against the problem's rest
  // derivative: the coupled strains follow the rest through the tensions.
  // The step's tension goes from that at 6 % stretch to that at 8 % (or 4 %),
  // and nothing is pinned, so that no triangle sits on one of the law's kinks
  // (the tension staying as it was, or a tension of exactly zero, as a
  // triangle between two pins held in place would have).
  const TriangleMesh mesh = mesh::rectangle(0.15, 0.08, 3, 2, mesh::RectanglePattern::perturbed);
  const Fabric fabric = preset_fabric("cotton_twill");
  const std::vector<CreepMaterial> creep_materials = {
      {fabric.in(Direction::warp).creep, fabric.in(Direction::weft).creep}};
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Vector3d> noise(mesh.vertex_count());
  for (auto& n : noise)
    n = 2e-3 * Eigen::Vector3d(unit(random), unit(random), unit(random));
  const auto placed = [&](double stretch) {
    std::vector<Eigen::Vector3d> at(mesh.vertex_count());
    for (std::size_t v = 0; v < at.size(); ++v) {
      const Eigen::Vector3d& p = mesh.positions[v];
      at[v] = Eigen::Vector3d(p.x() * (1.0 + stretch),
                              p.y() * (1.0 + 0.3 * stretch) + 0.2 * stretch * p.x(),
                              0.01 * p.x() * p.y()) +
              noise[v];
    }
    return at;
  };
  std::vector<Eigen::Vector2d> delta_uv(mesh.vertex_count());
  for (auto& d : delta_uv)
    d = 5e-3 * Eigen::Vector2d(unit(random), unit(random));
  const RestChange change = rest_change_per_vertex(mesh, delta_uv);
  for (const auto model :
       {element::MembraneModel::baraff_witkin, element::MembraneModel::saint_venant_kirchhoff}) {
    for (const double stretch : {0.08, 0.04}) {
      SCOPED_TRACE(element::membrane_model_name(model) +
                   (stretch < 0.06 ? ", recovering" : ", loading"));
      ClothMaterial material(
          {fabric.in(Direction::warp).elastic, fabric.in(Direction::weft).elastic, 300.0, 0.2});
      material.membrane_model = model;
      ClothProblem problem(PETSC_COMM_WORLD, mesh, material, {});
      CreepCoupling creep(problem, creep_materials);
      Vec x = nullptr, exact = nullptr, held = nullptr, difference = nullptr;
      ASSERT_EQ(problem.create_solution(&x), 0);
      for (Vec* w : {&exact, &held, &difference})
        ASSERT_EQ(VecDuplicate(x, w), 0);
      ASSERT_EQ(problem.set_solution(placed(0.06), x), 0);
      ASSERT_EQ(creep.record_tensions(x), 0);
      ASSERT_EQ(problem.set_solution(placed(stretch), x), 0);
      std::vector<ElementCreep> committed;
      ASSERT_EQ(creep.gather(&committed), 0);
      creep.couple(60.0);
      ASSERT_EQ(problem.rest_derivative(x, change, exact), 0);
      const double h = 1e-4;
      ASSERT_EQ(VecSet(difference, 0.0), 0);
      for (const double side : {h, -h}) {
        const TriangleMesh moved = moved_rest(mesh, change, side);
        ClothProblem other(PETSC_COMM_WORLD, moved, material, {});
        CreepCoupling other_creep(other, creep_materials);
        other_creep.restore(committed);
        other_creep.couple(60.0);
        Vec y = nullptr, f = nullptr;
        ASSERT_EQ(other.create_solution(&y), 0);
        ASSERT_EQ(VecDuplicate(y, &f), 0);
        ASSERT_EQ(VecCopy(x, y), 0); // one rank, the same numbering
        ASSERT_EQ(other.residual(y, f), 0);
        ASSERT_EQ(VecAXPY(difference, side > 0 ? 0.5 / h : -0.5 / h, f), 0);
        VecDestroy(&y);
        VecDestroy(&f);
      }
      PetscReal size = 0.0, error = 0.0, held_error = 0.0;
      ASSERT_EQ(VecNorm(exact, NORM_2, &size), 0);
      creep.uncouple(); // the held strains' derivative misses dF/dn dn/dX
      ASSERT_EQ(problem.rest_derivative(x, change, held), 0);
      ASSERT_EQ(VecAXPY(held, -1.0, difference), 0);
      ASSERT_EQ(VecNorm(held, NORM_2, &held_error), 0);
      ASSERT_EQ(VecAXPY(difference, -1.0, exact), 0);
      ASSERT_EQ(VecNorm(difference, NORM_2, &error), 0);
      EXPECT_GT(size, 0.0);
      EXPECT_LT(error, 1e-6 * size);
      EXPECT_GT(held_error, 1e-3 * size);
      for (Vec* w : {&x, &exact, &held, &difference})
        VecDestroy(w);
    }
  }
}

TEST(Checkpoint, RoundTripsEveryField) {
  RunCheckpoint written;
  written.time = 12.5;
  written.next_step = 0.25;
  written.step = 42;
  written.load_factor = 0.75;
  written.positions = {{0.1, 0.2, 0.3}, {1.0 / 3.0, -2.0, 1e-300}};
  written.velocities = {{1, 2, 3}, {4, 5, 6}};
  ElementCreep element;
  element.warp = {0.01, 0.002};
  element.weft = {0.003, 0.0004};
  element.tension_warp = 123.456;
  element.tension_weft = -1.0;
  written.creep = {element, ElementCreep{}};
  written.anchors = {{0, 1, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0}};
  written.history = "time_s,x\n0,1\n";
  const std::string path = "test_checkpoint_roundtrip.h5";
  write_checkpoint(path, written);
  const RunCheckpoint read = read_checkpoint(path);
  std::remove(path.c_str());
  EXPECT_EQ(read.time, written.time);
  EXPECT_EQ(read.next_step, written.next_step);
  EXPECT_EQ(read.step, written.step);
  EXPECT_EQ(read.load_factor, written.load_factor);
  ASSERT_EQ(read.positions.size(), 2u);
  EXPECT_EQ(read.positions[1], written.positions[1]);
  EXPECT_EQ(read.velocities[0], written.velocities[0]);
  ASSERT_EQ(read.creep.size(), 2u);
  EXPECT_EQ(read.creep[0].warp.permanent, 0.002);
  EXPECT_EQ(read.creep[0].weft.viscoelastic, 0.003);
  EXPECT_EQ(read.creep[0].tension_warp, 123.456);
  ASSERT_EQ(read.anchors.size(), 1u);
  EXPECT_EQ(read.anchors[0][7], 1.0);
  EXPECT_EQ(read.history, written.history);
}

TEST(Checkpoint, RejectsWhatIsNotACheckpoint) {
  const std::string path = "test_checkpoint_garbage.h5";
  std::ofstream(path) << "not HDF5\n";
  try {
    read_checkpoint(path);
    ADD_FAILURE() << "a text file was read as a checkpoint";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path + ": cannot open as an HDF5 checkpoint"),
              std::string::npos)
        << error.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW(read_checkpoint("no_such_checkpoint.h5"), InputError);
}

// The bytes of a file, and the file written back from them.
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// The bytes of a double, to find where a file holds it.
std::string bytes_of(double value) {
  std::string bytes(sizeof value, '\0');
  std::memcpy(bytes.data(), &value, sizeof value);
  return bytes;
}

// A checkpoint read back from `bytes` must be refused with a message naming
// the file (InputError), whatever the damage.
void expect_refused(const std::string& path, const std::string& bytes, const std::string& what) {
  write_bytes(path, bytes);
  try {
    read_checkpoint(path);
    ADD_FAILURE() << "a checkpoint with " << what << " was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(path + ": ", 0), 0u) << error.what();
  }
}

TEST(Checkpoint, CorruptedFilesAreRefused) {
  RunCheckpoint written;
  written.time = 12.5;
  written.next_step = 0.25;
  written.step = 7;
  // A value whose bytes occur once in the file: the bits flipped below.
  const double marker = 0.123456789012345678;
  written.positions = {{marker, 0.2, 0.3}, {0.4, 0.5, 0.6}};
  written.creep = {ElementCreep{}};
  written.history = "time_s,x\n0,1\n";
  const std::string path = "test_checkpoint_corrupted.h5";
  write_checkpoint(path, written);
  const std::string good = file_bytes(path);
  const std::string marker_bytes = bytes_of(marker);
  const std::size_t at = good.find(marker_bytes);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(good.find(marker_bytes, at + 1), std::string::npos);
  for (std::size_t bit = 0; bit < 8 * sizeof marker; ++bit) {
    std::string flipped = good;
    flipped[at + bit / 8] = char(flipped[at + bit / 8] ^ (1 << (bit % 8)));
    expect_refused(path, flipped, "bit " + std::to_string(bit) + " of a position flipped");
  }
  std::string zeroed_tail = good;
  std::fill(zeroed_tail.begin() + long(good.size() / 2), zeroed_tail.end(), '\0');
  expect_refused(path, zeroed_tail, "its second half zeroed");
  std::string garbage = good;
  for (std::size_t i = 0; i < garbage.size(); i += 97)
    garbage[i] = char(i * 31 + 7);
  expect_refused(path, garbage, "garbage bytes");
  expect_refused(path, good.substr(0, good.size() / 3), "its end cut off");
  write_bytes(path, good);
  EXPECT_EQ(read_checkpoint(path).positions[0].x(), marker); // the intact file still reads
  std::remove(path.c_str());
}

// The controller state of a dynamic run or static drape (/state) reads back
// exactly, and a changed character in it is refused like any corruption.
TEST(Checkpoint, StateRoundTripsAndIsSummed) {
  RunCheckpoint written;
  written.time = 0.5;
  written.next_step = 0.01;
  written.positions = {{0.1, 0.2, 0.3}};
  written.velocities = {{-1.0, 0.0, 2.5}};
  written.state = R"({"kind":"dynamic","control":{"next_output":0.30000000000000004}})";
  const std::string path = "test_checkpoint_state.h5";
  write_checkpoint(path, written);
  EXPECT_EQ(read_checkpoint(path).state, written.state);
  const std::string good = file_bytes(path);
  const std::size_t at = good.find("0.30000000000000004");
  ASSERT_NE(at, std::string::npos);
  std::string changed = good;
  changed[at + 2] = '4'; // 0.40000000000000004: still valid JSON, another state
  expect_refused(path, changed, "a digit of /state changed");
  std::remove(path.c_str());
  std::remove((path + ".tmp").c_str());
}

// The start of a finer drape level (/start_positions, optional) reads back
// exactly and is summed: a flipped bit in it is refused.
TEST(Checkpoint, StartPositionsRoundTripAndAreSummed) {
  RunCheckpoint written;
  written.next_step = 1.0;
  const double marker = 0.987654321098765432;
  written.positions = {{0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}};
  written.start_positions = {{0.7, marker, 0.9}, {1.0, 1.1, 1.2}};
  const std::string path = "test_checkpoint_start.h5";
  write_checkpoint(path, written);
  const RunCheckpoint read = read_checkpoint(path);
  ASSERT_EQ(read.start_positions.size(), 2u);
  EXPECT_EQ(read.start_positions[0].y(), marker);
  EXPECT_EQ(read.start_positions[1], written.start_positions[1]);
  const std::string good = file_bytes(path);
  const std::string marker_bytes = bytes_of(marker);
  const std::size_t at = good.find(marker_bytes);
  ASSERT_NE(at, std::string::npos);
  std::string flipped = good;
  flipped[at] = char(flipped[at] ^ 1);
  expect_refused(path, flipped, "a bit of a start position flipped");
  written.start_positions.clear();
  write_checkpoint(path, written);
  EXPECT_TRUE(read_checkpoint(path).start_positions.empty());
  std::remove(path.c_str());
}

// The checkpoint of the phase before (/before: a drape's last, which its
// wear's checkpoints carry) reads back whole and is summed: a flipped bit in
// it is refused. One phase nests, no more.
TEST(Checkpoint, PhaseBeforeRoundTripsAndIsSummed) {
  auto drape = std::make_shared<RunCheckpoint>();
  drape->next_step = 1.0;
  drape->step = 9;
  const double marker = 0.314159265358979312;
  drape->positions = {{0.1, marker, 0.3}};
  drape->start_positions = {{0.0, 0.5, 0.0}};
  drape->anchors = {AnchorRow{}};
  drape->state = R"({"kind":"static"})";
  RunCheckpoint written;
  written.time = 60.0;
  written.next_step = 12.0;
  written.step = 5;
  written.positions = {{0.1, 0.2, 0.25}};
  written.creep = {ElementCreep{}};
  written.state = R"({"kind":"wear"})";
  written.before = drape;
  const std::string path = "test_checkpoint_before.h5";
  write_checkpoint(path, written);
  const RunCheckpoint read = read_checkpoint(path);
  ASSERT_TRUE(read.before);
  EXPECT_EQ(read.time, 60.0);
  EXPECT_EQ(read.positions, written.positions);
  EXPECT_EQ(read.state, written.state);
  EXPECT_EQ(read.before->step, 9);
  EXPECT_EQ(read.before->positions[0].y(), marker);
  EXPECT_EQ(read.before->start_positions, drape->start_positions);
  EXPECT_EQ(read.before->anchors.size(), 1u);
  EXPECT_EQ(read.before->state, drape->state);
  EXPECT_FALSE(read.before->before);
  const std::string good = file_bytes(path);
  const std::string marker_bytes = bytes_of(marker);
  const std::size_t at = good.find(marker_bytes);
  ASSERT_NE(at, std::string::npos);
  std::string flipped = good;
  flipped[at + 3] = char(flipped[at + 3] ^ 4);
  expect_refused(path, flipped, "a bit of the phase before's positions flipped");
  RunCheckpoint twice = written;
  twice.before = std::make_shared<RunCheckpoint>(written); // whose own /before is the drape's
  EXPECT_THROW(write_checkpoint(path, twice), InputError);
  std::remove(path.c_str());
  std::remove((path + ".tmp").c_str());
}

} // namespace
} // namespace sartor
