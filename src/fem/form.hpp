#pragma once
// The discrete problem as a sum of energy forms (docs/architecture.md#forms).
//
// Every term of the cloth's energy is one form: membrane, bending, the
// distributed and point loads, contact with friction, seams, and any term a
// user adds (ClothProblem::add_form). A form gives its value, gradient and
// Hessian (PSD-projected unless the problem asks for the exact one) at a
// state, says which vertices it couples (for preallocation), and may carry
// state lagged from step to step (friction anchors), updated only once a
// step is accepted. ClothProblem sums the forms in a fixed order, applies
// the pins once, and hands the totals to the solvers.
//
// Three kinds, by where their terms live:
//   TriangleForm  a term integrated over each cloth triangle (membrane,
//                 gravity and pressure): the problem gathers a triangle's
//                 positions once and asks each triangle form in turn;
//   Form          any other term of this rank's local (ghosted) vector:
//                 elements of their own (hinges, patches), vertices (point
//                 loads, contact); the DM sums the ranks' shares;
//   CouplingForm  a term between vertices on any ranks, in global indices
//                 (seams).

#include "element/element.hpp"
#include "element/membrane.hpp"
#include "fem/block_assembly.hpp"

#include <petscmat.h>
#include <petscvec.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor {

struct ClothMaterial;

// A change of the rest coordinates, per triangle corner as the mesh stores
// them (TriangleMesh::material_uv), m.
using RestChange = std::vector<std::array<Eigen::Vector2d, 3>>;

namespace fem {

using Matrix9 = Eigen::Matrix<double, 9, 9>;

// The line of the energy report (ClothEnergy) a form's energy is counted in;
// `inertia` is a time step's (fem/forms/inertia_form.hpp), not the cloth's.
enum class EnergyPart { membrane, bending, external, contact, seam, inertia };
constexpr int energy_part_count = 5; // the cloth's

// The state forms are evaluated at.
struct FormPoint {
  // Positions of this rank's local vector: three per vertex at the offsets
  // of ClothProblem's layout, pinned vertices at their places.
  const PetscScalar* x = nullptr;
  double load_factor = 1.0;
  // The true Hessian: no PSD projection of any term.
  bool exact_hessian = false;
};

// One cloth triangle as a triangle form sees it.
struct TriangleView {
  int index = 0; // in the mesh
  const ClothMaterial& material;
  const element::TriangleRest& rest;
  const std::array<Eigen::Vector2d, 3>& uv; // material coordinates of the corners, m
  const element::Vector9& x;                // corner positions
};

// Where forms declare their elements: every element whose Hessian block a
// form adds through ElementHessians, in the order it adds them (the problem
// preallocates the Jacobian from them and may scatter the blocks straight
// into its value arrays).
class ElementRegistry {
public:
  ElementRegistry(BlockPattern* pattern, ElementScatter* scatter)
      : pattern_(pattern), scatter_(scatter) {}
  template <std::size_t N>
  PetscErrorCode add(const std::array<PetscInt, N>& dofs) {
    if (pattern_) pattern_->add_element(dofs);
    if (scatter_) return scatter_->add_element(dofs);
    return 0;
  }

private:
  BlockPattern* pattern_;
  ElementScatter* scatter_;
};

// Where forms add the Hessian blocks of their registered elements, in
// registration order: into the value arrays when the Jacobian carries a
// scatter, through MatSetValuesLocal otherwise.
class ElementHessians {
public:
  ElementHessians(Mat J, ElementScatter* scatter) : J_(J), scatter_(scatter) {}
  template <int N>
  PetscErrorCode add(const std::array<PetscInt, N>& dofs,
                     const Eigen::Matrix<double, N, N>& block) {
    if (scatter_) return scatter_->add<N>(block);
    const Eigen::Matrix<double, N, N, Eigen::RowMajor> row_major = block;
    return MatSetValuesLocal(J_, N, dofs.data(), N, dofs.data(), row_major.data(), ADD_VALUES);
  }

private:
  Mat J_;
  ElementScatter* scatter_;
};

// A term integrated over the cloth's triangles, all of them.
class TriangleForm {
public:
  virtual ~TriangleForm() = default;
  virtual const char* name() const = 0;
  virtual EnergyPart part() const = 0;
  // Whether the form takes part in the sum now: a form standing in for
  // another in some states (the creep coupling for the membrane while a
  // creep step is coupled) is inactive in the others.
  virtual bool active() const { return true; }
  // Adds the triangle's energy to `sum` (a term of several pieces adds them
  // one by one).
  virtual void add_energy(const TriangleView& t, const FormPoint& at, double* sum) const = 0;
  virtual element::Vector9 gradient(const TriangleView& t, const FormPoint& at) const = 0;
  // Adds the triangle's Hessian (projected unless at.exact_hessian) to the
  // triangle's block, which the problem assembles once all triangle forms
  // have added theirs.
  virtual void add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const = 0;
  // Whether the gradient is that of energy() (not pressure on a surface
  // with a free edge, nor position-dependent unloaded lengths).
  virtual bool has_potential() const { return true; }
  // Whether the Hessian differs from the exact one unless at.exact_hessian.
  virtual bool projects(const ClothMaterial&) const { return false; }
  // The design sensitivity's mixed derivative: the change of the triangle's
  // gradient when its material coordinates move by `delta_uv`, at fixed
  // positions, d/de grad(x; uv + e delta_uv) at e = 0. Forms without one
  // say so (has_rest_derivative), and ClothProblem::rest_derivative refuses.
  virtual bool has_rest_derivative() const { return false; }
  virtual element::Vector9 rest_derivative(const TriangleView&, const FormPoint&,
                                           const std::array<Eigen::Vector2d, 3>&) const {
    return element::Vector9::Zero();
  }
};

// A term of this rank's local vector; the problem sums the ranks' shares.
class Form {
public:
  virtual ~Form() = default;
  virtual const char* name() const = 0;
  virtual EnergyPart part() const = 0;
  virtual bool active() const { return true; } // as TriangleForm::active
  // Adds this rank's share of the energy to `sum`.
  virtual void add_energy(const FormPoint& at, double* sum) const = 0;
  // Adds this rank's share of the gradient to the local vector f.
  virtual void add_gradient(const FormPoint& at, PetscScalar* f) const = 0;
  // The elements whose blocks add_element_hessians adds (none by default).
  virtual PetscErrorCode register_elements(ElementRegistry&) const { return 0; }
  virtual PetscErrorCode add_element_hessians(const FormPoint&, ElementHessians&) const {
    return 0;
  }
  // Blocks that are not elements (vertex terms), by MatSetValuesLocal into
  // J, after every form's element blocks. They must lie within the blocks
  // of the registered elements (a vertex's own block, an edge's).
  virtual PetscErrorCode add_hessian(const FormPoint&, Mat) const { return 0; }
  // Collective. Updates the state lagged from step to step (friction
  // anchors) at an accepted state; never inside Newton.
  virtual PetscErrorCode accept_step(const FormPoint&) { return 0; }
  virtual bool has_potential() const { return true; }
  virtual bool projects() const { return false; }
  // The change of this rank's share of the gradient when the material
  // coordinates move by `change` (per mesh triangle corner), at fixed
  // positions, added to the local vector f (see TriangleForm).
  virtual bool has_rest_derivative() const { return false; }
  virtual void add_rest_derivative(const FormPoint&, const RestChange&, PetscScalar*) const {}
};

// A term between vertices on any ranks, evaluated on global vectors.
class CouplingForm {
public:
  virtual ~CouplingForm() = default;
  virtual const char* name() const = 0;
  virtual EnergyPart part() const = 0;
  virtual bool active() const { return true; } // as TriangleForm::active
  // Collective: the whole energy, every rank the same.
  virtual PetscErrorCode energy(Vec x, double* energy) = 0;
  // Collective: adds the gradient to the global vector f.
  virtual PetscErrorCode add_gradient(Vec x, Vec f) = 0;
  // Adds the Hessian at x, in global indices (projected unless `exact`).
  virtual PetscErrorCode add_hessian(Vec x, bool exact, Mat J) = 0;
  // Records its couplings into `recording` (BlockPattern::recorder).
  virtual PetscErrorCode record_couplings(Mat recording) = 0;
  // Collective: the change of the gradient when the material coordinates
  // move by `change`, at fixed positions, added to the global vector f (see
  // TriangleForm).
  virtual bool has_rest_derivative() const { return false; }
  virtual PetscErrorCode add_rest_derivative(Vec, const RestChange&, Vec) { return 0; }
};

} // namespace fem
} // namespace sartor
