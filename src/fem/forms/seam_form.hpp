#pragma once
// Seam springs between any vertices of the cloth, on any ranks
// (fem/forms/seam_coupling.hpp), at the problem's sewing progress: while the
// garment is sewn the springs stiffen from a gentle pull to their own
// stiffness (docs/seams.md). Pinned vertices enter at their places.

#include "fem/form.hpp"
#include "fem/forms/seam_coupling.hpp"

#include <memory>

namespace sartor {
class ClothProblem;
}

namespace sartor::fem {

// The seams and stiffness settings the springs were built from
// (seam_springs): what their change with the pattern is computed from.
struct SeamDesign {
  std::vector<Seam> seams;
  SeamStiffness stiffness;
};

class SeamForm final : public CouplingForm {
public:
  // `assigned`: the index (in the full spring list) of each spring the
  // coupling assembles on this rank; `design`: where the springs came from,
  // null when they were given as they are.
  SeamForm(const ClothProblem& problem, std::unique_ptr<SeamCoupling> coupling,
           std::vector<std::size_t> assigned, std::unique_ptr<SeamDesign> design)
      : problem_(problem), coupling_(std::move(coupling)), assigned_(std::move(assigned)),
        design_(std::move(design)) {}
  const char* name() const override { return "seams"; }
  EnergyPart part() const override { return EnergyPart::seam; }
  PetscErrorCode energy(Vec x, double* energy) override;
  PetscErrorCode add_gradient(Vec x, Vec f) override;
  PetscErrorCode add_hessian(Vec x, bool exact, Mat J) override;
  PetscErrorCode record_couplings(Mat recording) override;
  // Exact, through seam_spring_changes, for springs built from a design and
  // sewn (their own stiffness; the sewing ramp's is not differentiated).
  bool has_rest_derivative() const override;
  PetscErrorCode add_rest_derivative(Vec x, const RestChange& change, Vec f) override;

  const SeamCoupling& coupling() const { return *coupling_; }
  // Collective: the largest gap of a spring at x, m.
  PetscErrorCode largest_gap(Vec x, double* gap);
  // Collective: adds the springs' pull on the pinned vertices.
  PetscErrorCode add_pin_reaction(Vec x, Eigen::Vector3d* reaction);

private:
  // The pins' places, with the springs set to the sewing progress of now.
  PetscErrorCode prepare(std::vector<Eigen::Vector3d>* places);

  const ClothProblem& problem_;
  std::unique_ptr<SeamCoupling> coupling_;
  std::vector<std::size_t> assigned_;
  std::unique_ptr<SeamDesign> design_;
};

} // namespace sartor::fem
