#pragma once
// Checks of a cloth case before it is solved: sizes a run cannot hold and
// setups whose equations are singular, answered with a message naming the
// option instead of a hang, an exhausted memory or a solver's traceback.

#include "app/cli.hpp"
#include "fem/cloth_problem.hpp"
#include "garment/pattern.hpp"
#include "mesh/triangle_mesh.hpp"
#include "solvers/statics.hpp"

#include <cstddef>
#include <vector>

namespace sartor {

// The most triangles a case's mesh may have (after its refinements): some
// 2 GB of Jacobian, far beyond what a cloth run on one machine solves.
constexpr std::size_t max_case_triangles = 4'000'000;

// The most steps a time span may be divided into (time steps, output
// states, checkpoints, samples): beyond this a run would not end in a day or
// would fill the disk.
constexpr double max_time_divisions = 1e7;
// The longest simulated time, s: some 300 years, beyond any cloth's creep.
constexpr double max_simulated_time = 1e10;

// Throws InputError naming both options when option `span_option`'s `span`
// divided into `step` (option `step_option`) gives more than
// max_time_divisions; a `step` of 0 means "no division".
void check_time_divisions(double span, const std::string& span_option, double step,
                          const std::string& step_option);
// Throws InputError when `time` (option `option`) exceeds max_simulated_time.
void check_simulated_time(double time, const std::string& option);

// Throws InputError when `triangles` refined `refinements` times (four
// children each) exceeds max_case_triangles; `what` names the options.
void check_mesh_size(double triangles, int refinements, const std::string& what);

// Throws InputError when meshing the pattern's panels at `edge_length` (option
// --edge-length) would give more than max_case_triangles; bounded from the
// curves' control points, before any mesher runs.
void check_panel_mesh_size(const garment::Pattern& pattern, double edge_length);

// PETSc calls a stop on a small Newton step (CONVERGED_SNORM_RELATIVE)
// converged whatever the residual: with a singular tangent (nothing pinned, a
// free panel) or a load far beyond the cloth's strength the residual stays
// where it started. A static solve whose final residual is not six orders
// below its initial one (nor below 1e-9 of the membrane force scale
// `force_scale`, N, for a solve that starts near equilibrium) is marked not
// converged, its reason saying so.
void reject_unmet_residual(double force_scale, StaticReport* report);

// A flat membrane without bending has no stiffness out of its plane at the
// flat start: Newton's tangent is singular in a `quasi_static` analysis
// (statics, creep without --creep-dynamics) that is not `pressurised`.
// Throws InputError saying so.
void reject_flat_membrane_without_bending(bool quasi_static, bool pressurised,
                                          const TriangleMesh& mesh,
                                          const std::vector<ClothMaterial>& materials,
                                          const std::vector<int>& pinned);

} // namespace sartor
