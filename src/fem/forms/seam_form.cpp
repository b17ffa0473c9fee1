#include "fem/forms/seam_form.hpp"

#include "fem/cloth_problem.hpp"

namespace sartor::fem {

PetscErrorCode SeamForm::prepare(std::vector<Eigen::Vector3d>* places) {
  PetscFunctionBeginUser;
  PetscCall(problem_.pin_places(places));
  coupling_->set_sewing_progress(problem_.sewing_progress());
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::energy(Vec x, double* energy) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(prepare(&places));
  PetscCall(coupling_->energy(x, places, energy));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::add_gradient(Vec x, Vec f) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(prepare(&places));
  PetscCall(coupling_->add_forces(x, places, f));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::add_hessian(Vec, bool, Mat J) {
  PetscFunctionBeginUser;
  coupling_->set_sewing_progress(problem_.sewing_progress()); // linear springs: no positions
  PetscCall(coupling_->add_jacobian(J));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::record_couplings(Mat recording) {
  return coupling_->add_pattern(recording);
}

bool SeamForm::has_rest_derivative() const {
  return design_ && problem_.sewing_progress() >= 1.0;
}

PetscErrorCode SeamForm::add_rest_derivative(Vec x, const RestChange& change, Vec f) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCheck(has_rest_derivative(), problem_.comm(), PETSC_ERR_SUP,
             "the seams have no rest derivative (given springs, or sewing)");
  const std::vector<SeamSpringChange> all =
      seam_spring_changes(problem_.mesh(), design_->seams, design_->stiffness, change);
  std::vector<SeamSpringChange> mine;
  for (std::size_t index : assigned_)
    mine.push_back(all[index]);
  PetscCall(prepare(&places));
  PetscCall(coupling_->add_rest_derivative(x, places, mine, f));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::largest_gap(Vec x, double* gap) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(problem_.pin_places(&places));
  PetscCall(coupling_->largest_gap(x, places, gap));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamForm::add_pin_reaction(Vec x, Eigen::Vector3d* reaction) {
  std::vector<Eigen::Vector3d> places;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  PetscFunctionBeginUser;
  PetscCall(prepare(&places));
  PetscCall(coupling_->pinned_force(x, places, &force));
  *reaction += force;
  PetscFunctionReturn(0);
}

} // namespace sartor::fem
