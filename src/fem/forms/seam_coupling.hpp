#pragma once
// Seam springs in the distributed assembly. A seam spring couples vertices
// that may live on different ranks and, in general, are not in one rank's
// ghosted local vector, so seams bypass the DMPlex local assembly:
//  * every rank knows the first global dof of every free vertex (owners
//    write, one Allreduce at setup; pinned vertices have none);
//  * each spring is assembled by exactly one rank, the owner of its emitting
//    vertex (vertices[0]);
//  * the positions a rank needs are fetched from the global solution vector
//    with one VecScatter built at setup (pinned vertices take their
//    prescribed places);
//  * forces go in with VecSetValues(ADD_VALUES) and Jacobian blocks with
//    MatSetValues on global indices (off-process rows are stashed and sent
//    by the assembly); the same couplings are added to the preallocation.

#include "element/element.hpp"
#include "mesh/seams.hpp"

#include <petscmat.h>
#include <petscvec.h>

#include <Eigen/Core>

#include <vector>

namespace sartor {

class SeamCoupling {
public:
  // Collective. `first_dof[v]`: first global dof of mesh vertex v, -1 when it
  // is pinned (the same on every rank); `pin_index[v]`: v's index in the pin
  // list, -1 when free; `assigned`: the springs this rank assembles;
  // `layout`: a global solution vector (only its layout is used).
  SeamCoupling(MPI_Comm comm, Vec layout, std::vector<SeamSpring> assigned,
               std::vector<PetscInt> first_dof, std::vector<int> pin_index);
  ~SeamCoupling();
  SeamCoupling(const SeamCoupling&) = delete;
  SeamCoupling& operator=(const SeamCoupling&) = delete;

  // Collective: the seam energy summed over all ranks, J.
  PetscErrorCode energy(Vec x, const std::vector<Eigen::Vector3d>& pin_places, double* energy);
  // Collective: f += seam forces (gradient of the seam energy).
  PetscErrorCode add_forces(Vec x, const std::vector<Eigen::Vector3d>& pin_places, Vec f);
  // Adds the seam Hessian blocks (constant in x) to J; call between
  // MatZeroEntries and MatAssemblyBegin.
  PetscErrorCode add_jacobian(Mat J) const;
  // The same nonzeros, into a MATPREALLOCATOR matrix before its assembly.
  PetscErrorCode add_pattern(Mat pattern) const;
  // Collective: f += the change of the seam forces at x when each assigned
  // spring's stiffness and edge parameter change by `changes` (one per
  // assigned spring, in their order), the springs at their own stiffness.
  PetscErrorCode add_rest_derivative(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                     const std::vector<SeamSpringChange>& changes, Vec f);
  // Collective: the largest seam gap over all springs, m.
  PetscErrorCode largest_gap(Vec x, const std::vector<Eigen::Vector3d>& pin_places, double* gap);
  // Collective: the sum of the seam forces on pinned vertices (their part of
  // the pin reaction), N.
  PetscErrorCode pinned_force(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                              Eigen::Vector3d* force);
  // Gradual sewing: at the start each spring's stiffness is lowered so that
  // it pulls with `tension` (N/m) times the seam length it sews across its
  // gap at `positions` (every mesh vertex; never stiffer than its own); as
  // set_sewing_progress goes from 0 to 1 it stiffens geometrically to its
  // own stiffness. Without start_sewing, or at progress 1, springs are
  // their own.
  void start_sewing(double tension, const std::vector<Eigen::Vector3d>& positions);
  void set_sewing_progress(double progress) { progress_ = progress; }
  // Springs (all ranks) that couple a vertex owned by another rank than the
  // one assembling them: the couplings the DMPlex overlap cannot see.
  PetscInt cross_rank_springs() const { return cross_rank_springs_; }

private:
  struct SpringState {
    double stiffness = 0.0; // N/m, at the current sewing progress
    double energy = 0.0;
    Eigen::VectorXd gradient; // zero unless asked for
  };
  // The stiffness of spring `index` at the current sewing progress, N/m.
  double stiffness(std::size_t index) const;
  // Positions of each assigned spring's vertices, stacked, in spring order.
  PetscErrorCode fetch(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                       std::vector<double>* stacked);
  // The global row of dof d of vertex v, -1 when pinned (ignored by PETSc).
  PetscInt global_row(int v, int d) const;
  // f += a vector on the spring's vertices (3 per vertex), its free rows.
  PetscErrorCode add_to_rows(const SeamSpring& spring, const Eigen::VectorXd& values, Vec f) const;
  // Calls visit(index, spring, positions) for each assigned spring, its
  // vertices' positions stacked (3 per vertex) at x.
  template <class Visit>
  PetscErrorCode for_each_placed(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                 const Visit& visit);
  template <class Visit>
  PetscErrorCode for_each_spring(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                 element::Want want, const Visit& visit);

  MPI_Comm comm_;
  std::vector<SeamSpring> springs_;
  std::vector<PetscInt> first_dof_;
  std::vector<int> pin_index_;
  std::vector<PetscInt> slot_; // per mesh vertex: its place in remote_ (x3), -1 if not fetched
  Vec remote_ = nullptr;       // sequential: the fetched free positions
  VecScatter fetch_ = nullptr;
  PetscInt cross_rank_springs_ = 0;
  std::vector<double> start_fraction_; // per spring: its start stiffness over its own
  double progress_ = 1.0;
};

} // namespace sartor
