#pragma once
// Checks of a cloth case before it is solved: sizes a run cannot hold and
// setups whose equations are singular, answered with a message naming the
// option instead of a hang, an exhausted memory or a solver's traceback.

#include "fem/cloth_problem.hpp"
#include "mesh/triangle_mesh.hpp"
#include "solvers/cli.hpp"

#include <cstddef>
#include <vector>

namespace sartor {

// The most triangles a case's mesh may have (after its refinements): some
// 2 GB of Jacobian, far beyond what a cloth run on one machine solves.
constexpr std::size_t max_case_triangles = 4'000'000;

// Throws InputError when `triangles` refined `refinements` times (four
// children each) exceeds max_case_triangles; `what` names the options.
void check_mesh_size(double triangles, int refinements, const std::string& what);

// A flat membrane without bending has no stiffness out of its plane at the
// flat start: Newton's tangent is singular (static and quasi-static creep
// analyses, no pressure). Throws InputError saying so.
void reject_flat_membrane_without_bending(const Options& options, const TriangleMesh& mesh,
                                          const std::vector<ClothMaterial>& materials,
                                          const std::vector<int>& pinned);

} // namespace sartor
