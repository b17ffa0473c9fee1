#pragma once
// A toy energy form, as docs/architecture.md adds one: linear springs that
// tie vertices to fixed points, E = k/2 |x_v - p|^2 each. This file is the
// whole of it; ClothProblem::add_form puts it in the sum.

#include "fem/cloth_problem.hpp"
#include "fem/form.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace sartor::testing {

class SpringToPointForm final : public fem::Form {
public:
  struct Spring {
    int vertex;
    Eigen::Vector3d point; // m
  };
  SpringToPointForm(const ClothProblem& problem, std::vector<Spring> springs, double stiffness)
      : problem_(problem), springs_(std::move(springs)), stiffness_(stiffness) {}
  const char* name() const override { return "spring to point"; }
  fem::EnergyPart part() const override { return fem::EnergyPart::external; }

  void add_energy(const fem::FormPoint& at, double* sum) const override {
    for (const Spring& s : springs_) {
      if (problem_.owns_vertex(s.vertex))
        *sum += 0.5 * stiffness_ * (position(at, s.vertex) - s.point).squaredNorm();
    }
  }
  void add_gradient(const fem::FormPoint& at, PetscScalar* f) const override {
    for (const Spring& s : springs_) {
      if (!problem_.owns_vertex(s.vertex)) continue;
      const Eigen::Vector3d force = stiffness_ * (position(at, s.vertex) - s.point);
      for (int d = 0; d < 3; ++d)
        f[problem_.vertex_offset(s.vertex) + d] += force[d];
    }
  }
  // k I on the vertex's own block (within the elements' pattern).
  PetscErrorCode add_hessian(const fem::FormPoint&, Mat J) const override {
    PetscFunctionBeginUser;
    for (const Spring& s : springs_) {
      if (!problem_.owns_vertex(s.vertex)) continue;
      const PetscInt first = problem_.vertex_offset(s.vertex);
      const PetscInt dofs[3] = {first, first + 1, first + 2};
      const double block[9] = {stiffness_, 0, 0, 0, stiffness_, 0, 0, 0, stiffness_};
      PetscCall(MatSetValuesLocal(J, 3, dofs, 3, dofs, block, ADD_VALUES));
    }
    PetscFunctionReturn(0);
  }

private:
  Eigen::Vector3d position(const fem::FormPoint& at, int vertex) const {
    const PetscInt first = problem_.vertex_offset(vertex);
    return {at.x[first], at.x[first + 1], at.x[first + 2]};
  }
  const ClothProblem& problem_;
  std::vector<Spring> springs_;
  double stiffness_; // N/m
};

} // namespace sartor::testing
