// sartor run: static equilibrium of a cloth described by a YAML case file.
// The case pipeline itself (solve_case) is shared with `sartor converge`.

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/cloth_output.hpp"
#include "fem/petsc_call.hpp"
#include "fem/statics.hpp"
#include "material/fabric.hpp"
#include "mesh/generators.hpp"
#include "mesh/obj.hpp"
#include "solvers/cloth_case.hpp"
#include "solvers/commands.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace sartor {

const std::vector<OptionSpec>& case_option_specs() {
  static const std::vector<OptionSpec> specs{
      {"mesh", "KIND", "rectangle", "rectangle, disk, cylinder_band, sphere_cap or obj"},
      {"mesh-file", "FILE", "", "OBJ file (mesh obj): texture coordinates give the rest shape"},
      {"mesh-width", "M", "1", "rectangle width (along warp), m"},
      {"mesh-height", "M", "1", "rectangle or band height (along weft), m"},
      {"mesh-nx", "N", "10", "rectangle divisions along the width"},
      {"mesh-ny", "N", "10", "rectangle divisions along the height"},
      {"mesh-pattern", "P", "alternating", "rectangle diagonals: alternating, right, perturbed"},
      {"mesh-radius", "M", "0.5", "disk, band or sphere radius, m"},
      {"mesh-rings", "N", "8", "disk or cap rings"},
      {"mesh-segments", "N", "32", "band segments around"},
      {"mesh-rows", "N", "8", "band rows along the axis"},
      {"mesh-cap-angle", "RAD", "0.5", "sphere cap half angle, rad"},
      {"mesh-refine", "N", "0", "uniform refinements (each splits triangles in four)"},
      {"mesh-snap-boundary", "", "",
       "disk: put refined boundary vertices back on the circle (position and uv)"},
      {"mesh-rotate-x", "DEG", "0", "rotate the placement about the x axis, degrees"},
      {"mesh-translate", "X,Y,Z", "0,0,0", "then translate it, m"},
      {"fabric", "SPEC", "cotton_twill", "preset or FILE.yaml: elastic curves per direction"},
      {"warp-modulus", "N/M", "", "linear warp modulus, N/m (replaces the fabric's curve)"},
      {"weft-modulus", "N/M", "", "linear weft modulus, N/m (replaces the fabric's curve)"},
      {"shear-modulus", "N/M", "", "in-plane shear modulus, N/m [0.1 sqrt(k_warp k_weft)]"},
      {"poisson", "NU", "0", "warp-weft Poisson coupling (stvk model)"},
      {"membrane-model", "M", "baraff_witkin", "baraff_witkin or stvk"},
      {"membrane-psd", "", "", "project membrane Hessians to PSD (compression stabilisation)"},
      {"bending-model", "M", "discrete_shell", "discrete_shell or quadratic"},
      {"bending-stiffness", "N*M", "1e-6", "bending stiffness, N m (0: no bending)"},
      {"bending-psd", "", "", "project bending Hessians to PSD"},
      {"density", "KG/M2", "0.2", "areal density, kg/m^2"},
      {"gravity", "X,Y,Z", "0,0,-9.80665", "gravitational acceleration, m/s^2"},
      {"pressure", "PA", "0", "follower pressure on the triangles' normal side, Pa"},
      {"point-force", "V,FX,FY,FZ", "", "a force (N) on vertex V"},
      {"pin-box", "X0,X1,Y0,Y1,Z0,Z1", "", "pin the vertices inside these boxes (6 numbers each)"},
      {"pin-boundary", "", "", "pin every boundary vertex"},
      {"pin-vertices", "I,J,...", "", "pin these vertices"},
      {"pin-move", "X,Y,Z", "0,0,0", "move the pins by this much as the load ramps, m"},
      {"probe", "X,Y,Z", "", "report the displacement of the vertex nearest this point"},
      {"load-steps", "N", "1", "load increments (each halved up to 8 times on failure)"},
  };
  return specs;
}

const CommandSpec& run_command() {
  static const CommandSpec spec{
      "run",
      "static equilibrium of a cloth case (YAML options file)",
      "sartor run CASE.yaml [--option value ...] [-petsc_option ...]",
      "Builds the mesh, material, pins and loads the case describes, solves static\n"
      "equilibrium with Newton's method (PETSc SNES; loads ramped in --load-steps,\n"
      "failed steps cut back), and writes the result. CASE.yaml holds the options\n"
      "below without their dashes (load_steps: 4); options on the command line win.\n\n"
      "Output in DIR: result.h5 + result.xmf (open the .xmf in ParaView: positions,\n"
      "displacement, per-triangle strain and tension in warp and weft), final.obj,\n"
      "summary.json (energies, iterations, residuals, reactions, timings),\n"
      "petsc_options.txt (every option in effect).\n\n"
      "examples:\n"
      "  sartor run cases/fe/hanging_sheet.yaml\n"
      "  sartor run cases/fe/hencky.yaml --mesh-rings 16 -snes_monitor\n"
      "  mpiexec -n 2 sartor run cases/fe/hanging_sheet.yaml",
      [] {
        std::vector<OptionSpec> options = case_option_specs();
        options.push_back(
            {"output", "DIR", "out/run", "output folder (created; files in it are replaced)"});
        return options;
      }(),
      1,
      true};
  return spec;
}

namespace {

std::vector<double> numbers(const Options& options, const std::string& name, std::size_t count) {
  const std::string text = options.text(name);
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(values.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("option --" + name + ": '" + item + "' is not a number");
    }
  }
  if (count != 0 && values.size() != count) {
    throw InputError("option --" + name + ": expected " + std::to_string(count) +
                     " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

Eigen::Vector3d vector3(const Options& options, const std::string& name) {
  const auto v = numbers(options, name, 3);
  return {v[0], v[1], v[2]};
}

int count_option(const Options& options, const std::string& name, long minimum) {
  const long value = options.integer(name);
  if (value < minimum) {
    throw InputError("option --" + name + ": must be >= " + std::to_string(minimum) + ", got " +
                     options.text(name));
  }
  return int(value);
}

// Moves the boundary vertices of a disk of `radius` centred at the origin
// radially onto its circle, in position and in every corner's uv (disk: uv = x, y).
void snap_to_circle(TriangleMesh& cloth, double radius) {
  std::vector<bool> boundary(cloth.vertex_count(), false);
  for (int v : boundary_vertices(cloth)) {
    boundary[std::size_t(v)] = true;
    Eigen::Vector3d& p = cloth.positions[std::size_t(v)];
    const double r = std::hypot(p.x(), p.y());
    if (r > 0.0) p.head<2>() *= radius / r;
  }
  for (std::size_t t = 0; t < cloth.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (!boundary[std::size_t(cloth.triangles[t][c])]) continue;
      Eigen::Vector2d& uv = cloth.material_uv[t][c];
      if (uv.norm() > 0.0) uv *= radius / uv.norm();
    }
  }
}

// The mesh the options describe, with `extra_refinements` more uniform
// refinements than --mesh-refine asks for; `refinements` gets the total.
TriangleMesh build_mesh(const Options& options, int extra_refinements, int* refinements) {
  const std::string kind = options.text("mesh");
  TriangleMesh cloth;
  if (kind == "rectangle") {
    cloth =
        mesh::rectangle(options.positive_real("mesh-width"), options.positive_real("mesh-height"),
                        count_option(options, "mesh-nx", 1), count_option(options, "mesh-ny", 1),
                        mesh::rectangle_pattern(options.text("mesh-pattern")));
  } else if (kind == "disk") {
    cloth =
        mesh::disk(options.positive_real("mesh-radius"), count_option(options, "mesh-rings", 1));
  } else if (kind == "cylinder_band") {
    cloth = mesh::cylinder_band(
        options.positive_real("mesh-radius"), options.positive_real("mesh-height"),
        count_option(options, "mesh-segments", 3), count_option(options, "mesh-rows", 1));
  } else if (kind == "sphere_cap") {
    cloth = mesh::sphere_cap(options.positive_real("mesh-radius"),
                             options.positive_real("mesh-cap-angle"),
                             count_option(options, "mesh-rings", 1));
  } else if (kind == "obj") {
    if (!options.is_set("mesh-file")) throw InputError("mesh obj needs --mesh-file FILE.obj");
    cloth = read_obj(options.text("mesh-file"));
  } else {
    throw InputError("option --mesh: unknown kind '" + kind +
                     "' (rectangle, disk, cylinder_band, sphere_cap, obj)");
  }
  const bool snap = options.flag("mesh-snap-boundary");
  if (snap && kind != "disk") {
    throw InputError("option --mesh-snap-boundary applies to --mesh disk only (the mesh is " +
                     kind + ")");
  }
  *refinements = count_option(options, "mesh-refine", 0) + extra_refinements;
  for (int level = *refinements; level > 0; --level) {
    cloth = mesh::refine(cloth);
    if (snap) snap_to_circle(cloth, options.positive_real("mesh-radius"));
  }
  const double angle = options.real("mesh-rotate-x") * M_PI / 180.0;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d shift = vector3(options, "mesh-translate");
  for (auto& p : cloth.positions)
    p = rotation * p + shift;
  return cloth;
}

ClothMaterial build_material(const Options& options) {
  const auto choices = resolve_fabrics(options.text("fabric"));
  const Fabric& fabric = choices.front().fabric;
  const auto curve = [&](const char* option, Direction direction) {
    if (options.is_set(option)) {
      return TensionCurve::linear(options.positive_real(option), std::string("--") + option);
    }
    return fabric.in(direction).elastic;
  };
  ClothMaterial material({curve("warp-modulus", Direction::warp),
                          curve("weft-modulus", Direction::weft), 0.0, options.real("poisson")});
  material.membrane.shear_modulus = options.is_set("shear-modulus")
                                        ? options.nonnegative_real("shear-modulus")
                                        : 0.1 * std::sqrt(material.membrane.warp.initial_modulus() *
                                                          material.membrane.weft.initial_modulus());
  const std::string membrane = options.text("membrane-model");
  if (membrane == "baraff_witkin") {
    material.membrane_model = element::MembraneModel::baraff_witkin;
  } else if (membrane == "stvk") {
    material.membrane_model = element::MembraneModel::saint_venant_kirchhoff;
  } else {
    throw InputError("option --membrane-model: unknown model '" + membrane +
                     "' (baraff_witkin, stvk)");
  }
  const std::string bending = options.text("bending-model");
  if (bending == "discrete_shell") {
    material.bending_model = element::BendingModel::discrete_shell;
  } else if (bending == "quadratic") {
    material.bending_model = element::BendingModel::quadratic;
  } else {
    throw InputError("option --bending-model: unknown model '" + bending +
                     "' (discrete_shell, quadratic)");
  }
  material.bending_stiffness = options.nonnegative_real("bending-stiffness");
  material.areal_density = options.nonnegative_real("density");
  material.project_membrane = options.flag("membrane-psd");
  material.project_bending = options.flag("bending-psd");
  return material;
}

std::vector<int> pinned_vertices(const Options& options, const TriangleMesh& mesh) {
  std::vector<bool> pin(mesh.vertex_count(), false);
  if (options.is_set("pin-box")) {
    const auto boxes = numbers(options, "pin-box", 0);
    if (boxes.empty() || boxes.size() % 6 != 0) {
      throw InputError("option --pin-box: expected 6 numbers per box (x0,x1,y0,y1,z0,z1), got " +
                       std::to_string(boxes.size()));
    }
    for (std::size_t b = 0; b < boxes.size(); b += 6) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        bool inside = true;
        for (std::size_t d = 0; d < 3; ++d) {
          const double coordinate = mesh.positions[v][long(d)];
          inside = inside && coordinate >= boxes[b + 2 * d] && coordinate <= boxes[b + 2 * d + 1];
        }
        if (inside) pin[v] = true;
      }
    }
  }
  if (options.flag("pin-boundary")) {
    for (int v : boundary_vertices(mesh))
      pin[std::size_t(v)] = true;
  }
  if (options.is_set("pin-vertices")) {
    for (double value : numbers(options, "pin-vertices", 0)) {
      const auto v = long(value);
      if (double(v) != value || v < 0 || std::size_t(v) >= mesh.vertex_count()) {
        throw InputError("option --pin-vertices: " + format_number(value) +
                         " is not a vertex of the mesh (0.." +
                         std::to_string(mesh.vertex_count() - 1) + ")");
      }
      pin[std::size_t(v)] = true;
    }
  }
  std::vector<int> pinned;
  for (std::size_t v = 0; v < pin.size(); ++v) {
    if (pin[v]) pinned.push_back(int(v));
  }
  return pinned;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v[0], v[1], v[2]};
}

// The longest triangle edge in material coordinates, m.
double longest_material_edge(const TriangleMesh& mesh) {
  double longest = 0.0;
  for (const auto& uv : mesh.material_uv) {
    for (std::size_t c = 0; c < 3; ++c)
      longest = std::max(longest, (uv[(c + 1) % 3] - uv[c]).norm());
  }
  return longest;
}

void broadcast(double* values, int count) {
  MPI_Bcast(values, count, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
}

} // namespace

CaseResult solve_case(const Options& options, int extra_refinements) {
  const auto started = std::chrono::steady_clock::now();
  CaseResult result;
  result.mesh = build_mesh(options, extra_refinements, &result.mesh_refine);
  const TriangleMesh& mesh = result.mesh;
  const ClothMaterial material = build_material(options);
  const std::vector<int> pinned = pinned_vertices(options, mesh);
  result.pinned_vertices = pinned.size();
  result.h = longest_material_edge(mesh);

  ClothProblem problem(PETSC_COMM_WORLD, mesh, material, pinned);
  problem.loads.gravity = vector3(options, "gravity");
  problem.loads.pressure = options.real("pressure");
  if (options.is_set("point-force")) {
    const auto f = numbers(options, "point-force", 4);
    const auto v = long(f[0]);
    if (double(v) != f[0] || v < 0 || std::size_t(v) >= mesh.vertex_count()) {
      throw InputError("option --point-force: vertex " + format_number(f[0]) +
                       " is not in the mesh");
    }
    problem.loads.point_forces.push_back({int(v), Eigen::Vector3d(f[1], f[2], f[3])});
  }
  problem.pin_motion = vector3(options, "pin-move");
  StaticOptions solve;
  solve.load_steps = count_option(options, "load-steps", 1);
  if (options.is_set("probe")) {
    CaseProbe probe;
    probe.point = vector3(options, "probe");
    for (std::size_t v = 1; v < mesh.vertex_count(); ++v) {
      if ((mesh.positions[v] - probe.point).norm() <
          (mesh.positions[probe.vertex] - probe.point).norm())
        probe.vertex = v;
    }
    probe.initial_position = mesh.positions[probe.vertex];
    probe.displacement.setZero();
    result.probe = probe;
  }
  result.dofs = problem.global_dof_count();
  const auto set_up = std::chrono::steady_clock::now();

  Vec x = nullptr;
  SartorPetscCall(problem.create_solution(&x));
  SartorPetscCall(solve_static(problem, x, solve, &result.report));
  result.converged = result.report.converged;
  result.load_factor = problem.load_factor;
  result.solve_seconds = result.report.solve_seconds;

  SartorPetscCall(problem.energy(x, &result.energy));
  SartorPetscCall(problem.pin_reaction(x, &result.pin_reaction));
  SartorPetscCall(problem.gather_positions(x, &result.positions));
  SartorPetscCall(problem.gather_strains(x, &result.strains));
  SartorPetscCall(VecDestroy(&x));

  // Rank 0 holds the positions: it measures, everybody learns.
  double measured[4] = {0.0, 0.0, 0.0, 0.0};
  if (is_root()) {
    for (std::size_t v = 0; v < result.positions.size(); ++v) {
      measured[0] = std::max(measured[0], (result.positions[v] - mesh.positions[v]).norm());
    }
    if (result.probe) {
      const Eigen::Vector3d d =
          result.positions[result.probe->vertex] - mesh.positions[result.probe->vertex];
      measured[1] = d.x();
      measured[2] = d.y();
      measured[3] = d.z();
    }
  }
  broadcast(measured, 4);
  result.max_displacement = measured[0];
  if (result.probe) result.probe->displacement = {measured[1], measured[2], measured[3]};
  const auto finished = std::chrono::steady_clock::now();
  result.setup_seconds = std::chrono::duration<double>(set_up - started).count();
  result.total_seconds = std::chrono::duration<double>(finished - started).count();
  return result;
}

void add_case_summary(const CaseResult& result, nlohmann::json& summary) {
  const StaticReport& report = result.report;
  summary["mesh"] = {{"vertices", result.mesh.vertex_count()},
                     {"triangles", result.mesh.triangle_count()},
                     {"pinned_vertices", result.pinned_vertices},
                     {"dofs", result.dofs}};
  summary["converged"] = report.converged;
  summary["solver"] = {{"reason", report.reason},
                       {"load_steps", report.steps.size()},
                       {"newton_iterations", report.newton_iterations},
                       {"linear_iterations", report.linear_iterations},
                       {"initial_residual_norm", report.initial_residual_norm},
                       {"final_residual_norm", report.final_residual_norm}};
  summary["load_steps"] = nlohmann::json::array();
  for (const auto& step : report.steps) {
    summary["load_steps"].push_back({{"load_factor", step.load_factor},
                                     {"converged", step.converged},
                                     {"reason", step.reason},
                                     {"newton_iterations", step.newton_iterations},
                                     {"linear_iterations", step.linear_iterations},
                                     {"residual_norm", step.residual_norm}});
  }
  summary["energy_J"] = {{"membrane", result.energy.membrane},
                         {"bending", result.energy.bending},
                         {"external", result.energy.external},
                         {"total", result.energy.total()}};
  summary["pin_reaction_N"] = vector_json(result.pin_reaction);
  summary["max_displacement_m"] = result.max_displacement;
  if (result.probe) {
    summary["probe"] = {{"vertex", result.probe->vertex},
                        {"initial_position_m", vector_json(result.probe->initial_position)},
                        {"displacement_m", vector_json(result.probe->displacement)}};
  }
  summary["timing_s"] = {{"setup", result.setup_seconds},
                         {"solve", result.solve_seconds},
                         {"total", result.total_seconds}};
}

void write_case_results(const std::string& directory, const CaseResult& result,
                        const nlohmann::json& summary) {
  if (!is_root()) return;
  write_cloth_results(directory, result.mesh, result.positions, result.strains);
  write_json(directory + "/summary.json", summary);
}

void write_petsc_options(const std::string& directory) {
  PetscViewer viewer = nullptr;
  SartorPetscCall(
      PetscViewerASCIIOpen(PETSC_COMM_WORLD, (directory + "/petsc_options.txt").c_str(), &viewer));
  SartorPetscCall(PetscOptionsView(nullptr, viewer));
  SartorPetscCall(PetscViewerDestroy(&viewer));
}

int run_run(const Invocation& invocation) {
  const Options& options = invocation.options;
  const CaseResult result = solve_case(options);

  nlohmann::json summary = run_metadata(invocation, "run");
  summary["case"] = invocation.command_line.positionals.at(0);
  add_case_summary(result, summary);
  const std::string directory = options.text("output");
  write_case_results(directory, result, summary);
  write_petsc_options(directory);

  SartorPetscCall(
      PetscPrintf(PETSC_COMM_WORLD,
                  "sartor run: %zu triangles, %s after %d Newton iterations in %zu load "
                  "step(s), residual %.3e; wrote %s\n",
                  result.mesh.triangle_count(), result.report.reason.c_str(),
                  int(result.report.newton_iterations), result.report.steps.size(),
                  result.report.final_residual_norm, directory.c_str()));
  if (!result.converged) {
    throw InputError("the static solve did not converge (" + result.report.reason +
                     " at load factor " + format_number(result.load_factor) + "); " + directory +
                     " holds the last converged state. Try more --load-steps or -snes_monitor");
  }
  return 0;
}

} // namespace sartor
