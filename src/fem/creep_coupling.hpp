#pragma once
// The creep state of a cloth's elements (thesis §5.3, Algorithm 2): every
// triangle carries, in warp and weft, the viscoelastic and permanent strains
// of the creep law (material/creep_law.hpp), and the unloaded lengths
// 1 + eps_v + eps_p that the membrane measures its elastic strain from
// (ClothProblem::nonelastic).
//
// Staggered coupling: equilibrium is solved with the unloaded lengths frozen;
// then each element's state advances over the step with its tension taken
// linear in time from the tension recorded at the step's start to the tension
// at the step's solved end. The law is integrated exactly for such a tension,
// so under a tension held constant (dead load on a uniform strip) the result
// does not depend on the step size.
//
// Monolithic coupling: the creep update sits inside the residual. Each
// element's non-elastic strains at the step's end solve, at the current
// positions, n = N(T(x, n)), N the exact step of the law from the committed
// state with the tension going linearly to T, T the element's tension with
// unloaded lengths 1 + n; Newton's tangent includes dF/dn dn/dx, with dn/dx
// from the implicit function theorem (exact: the law's derivative comes from
// forward-mode automatic differentiation, the membrane's from
// membrane_creep_sensitivity).
//
// Tension is the membrane's: force per unit unloaded width, N/m
// (element::membrane_strain). A trial advance can be rolled back, so a step
// that fails (or whose creep increment is too large) leaves no trace.
//
// Each rank advances the triangles it assembles; the state of every triangle
// is kept on every rank's ClothProblem::nonelastic only for the owned ones.

#include "fem/cloth_problem.hpp"
#include "material/creep_law.hpp"

#include <petscvec.h>

#include <vector>

namespace sartor {

struct CreepMaterial {
  CreepParameters warp;
  CreepParameters weft;
};

// One element's creep state and the tension its next step starts from.
struct ElementCreep {
  CreepState warp;
  CreepState weft;
  double tension_warp = 0.0; // N/m
  double tension_weft = 0.0; // N/m
};

class CreepCoupling : public NonelasticResponse {
public:
  // `materials`: one per mesh material id, as the problem's ClothMaterials.
  CreepCoupling(ClothProblem& problem, std::vector<CreepMaterial> materials);

  // Collective: the tensions at x become those the next step starts from.
  PetscErrorCode record_tensions(Vec x);
  // Collective: advances every element from the committed state over `dt`
  // seconds, the tension going linearly from the recorded one to that at x,
  // and sets the problem's unloaded lengths to the trial state. `increment`:
  // the largest change of a non-elastic strain (eps_v + eps_p) of any element.
  PetscErrorCode advance(Vec x, double dt, double* increment);
  // Monolithic: from now on the problem's residual takes each element's
  // unloaded lengths from its creep step of `dt` seconds from the committed
  // state to the tension at the current positions (dt = 0: the committed
  // state held). Makes this the problem's nonelastic_response.
  void couple(double dt);
  // Collective, monolithic: the step's end state at the solved positions x
  // becomes the trial state (as advance() does for the staggered scheme),
  // which the residual then holds fixed until commit() or roll_back().
  PetscErrorCode advance_coupled(Vec x, double* increment);
  // Stops the monolithic coupling: the residual uses the problem's frozen
  // unloaded lengths again.
  void uncouple();

  // The trial state becomes the committed one (its tensions those at x of
  // the last advance).
  void commit();
  // Back to the committed state.
  void roll_back();

  Answer respond(int triangle, const ClothMaterial& material, const element::TriangleRest& rest,
                 const element::Vector9& x, bool want_derivative) const override;
  bool moves_with_positions() const override { return !holding_trial_ && coupled_dt_ > 0.0; }

  // Collective: the committed state of every triangle, in mesh numbering, on
  // rank 0 (empty elsewhere).
  PetscErrorCode gather(std::vector<ElementCreep>* states) const;
  // The committed state of every triangle (the same on every rank), e.g.
  // from a checkpoint. Throws InputError when the count does not match.
  void restore(const std::vector<ElementCreep>& states);

private:
  void apply(const std::vector<ElementCreep>& states);
  const CreepMaterial& material_of(int triangle) const;
  // One element's monolithic step from `from` over `dt` at positions x: its
  // end state, and when asked dn/dx and dn/dT. Not converged: NaN strains.
  struct CoupledStep {
    ElementCreep state;
    Eigen::Matrix<double, 2, 9> per_position = Eigen::Matrix<double, 2, 9>::Zero();
    Eigen::Matrix2d per_tension = Eigen::Matrix2d::Zero();
  };
  CoupledStep coupled_step(const ElementCreep& from, double dt, const CreepMaterial& creep,
                           const ClothMaterial& material, const element::TriangleRest& rest,
                           const element::Vector9& x, bool want_derivative) const;

  ClothProblem& problem_;
  std::vector<CreepMaterial> materials_;
  std::vector<int> owned_;              // mesh triangles this rank assembles
  std::vector<ElementCreep> committed_; // per mesh triangle (owned ones meaningful)
  std::vector<ElementCreep> trial_;     // per mesh triangle
  // The monolithic step the residual takes: from the committed state over
  // coupled_dt_, or the trial state held (after advance_coupled).
  double coupled_dt_ = 0.0;
  bool holding_trial_ = false;
};

} // namespace sartor
