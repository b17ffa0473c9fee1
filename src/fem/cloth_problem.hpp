#pragma once
// A cloth on PETSc: the triangle mesh as a distributed DMPlex with three
// position dofs per vertex, pinned vertices as section constraints, and the
// assembly of energy, residual and Jacobian from the element kernels.
//
// The unknowns are the vertex positions x (not displacements). The residual
// is F(x) = grad E(x) - f_ext(x): membrane and bending energies minus gravity,
// point forces and follower pressure, the loads scaled by a load factor.
//
// Every rank holds the whole TriangleMesh (it is the serial front end's
// output); the DMPlex decides which triangles each rank assembles. Results
// are gathered in the mesh's own vertex and triangle numbering, so they do not
// depend on the number of ranks.

#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "mesh/triangle_mesh.hpp"

#include <petscdmplex.h>
#include <petscmat.h>
#include <petscsf.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor {

struct ClothMaterial {
  explicit ClothMaterial(element::MembraneMaterial membrane_material)
      : membrane(std::move(membrane_material)) {}
  element::MembraneModel membrane_model = element::MembraneModel::baraff_witkin;
  element::MembraneMaterial membrane;
  element::BendingModel bending_model = element::BendingModel::discrete_shell;
  double bending_stiffness = 0.0; // N m
  double areal_density = 0.0;     // kg/m^2
  bool project_membrane = false;  // PSD-project element Hessians (compression stabilisation)
  bool project_bending = false;
};

struct ClothLoads {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();         // m/s^2
  double pressure = 0.0;                                     // Pa, follower
  std::vector<std::pair<int, Eigen::Vector3d>> point_forces; // vertex, N
};

// Energy, split for reports.
struct ClothEnergy {
  double membrane = 0.0;
  double bending = 0.0;
  double external = 0.0; // potential of gravity and point forces (no pressure)
  double total() const { return membrane + bending + external; }
};

// Per-triangle results in mesh numbering.
struct TriangleField {
  std::vector<element::MembraneStrain> strain;
};

class ClothProblem {
public:
  // Collective. `mesh`, `pinned` (vertex indices) must be the same on every rank.
  ClothProblem(MPI_Comm comm, const TriangleMesh& mesh, const ClothMaterial& material,
               const std::vector<int>& pinned);
  ~ClothProblem();
  ClothProblem(const ClothProblem&) = delete;
  ClothProblem& operator=(const ClothProblem&) = delete;

  MPI_Comm comm() const { return comm_; }
  DM dm() const { return dm_; }
  const TriangleMesh& mesh() const { return mesh_; }
  ClothLoads loads;
  double load_factor = 1.0;
  std::vector<element::NonelasticStrain> nonelastic; // per mesh triangle (creep state)

  // A global vector of the free positions, filled from the mesh's placement.
  PetscErrorCode create_solution(Vec* x) const;
  // Moves pinned vertex `index` (in the order given to the constructor).
  void set_pin_position(std::size_t index, const Eigen::Vector3d& position);
  // Every pin is displaced by load_factor * pin_motion from its position.
  Eigen::Vector3d pin_motion = Eigen::Vector3d::Zero();
  const std::vector<int>& pinned() const { return pinned_; }

  PetscErrorCode residual(Vec x, Vec f);
  PetscErrorCode jacobian(Vec x, Mat J);
  PetscErrorCode energy(Vec x, ClothEnergy* energy);
  // Preallocated exactly for the element couplings (membrane and hinges).
  PetscErrorCode create_jacobian(Mat* J);
  bool has_follower_load() const { return loads.pressure != 0.0; }

  // All vertex positions, in mesh numbering, on rank 0 (empty elsewhere).
  PetscErrorCode gather_positions(Vec x, std::vector<Eigen::Vector3d>* positions);
  // Strains and tensions of every triangle, in mesh numbering, on rank 0.
  PetscErrorCode gather_strains(Vec x, std::vector<element::MembraneStrain>* strains);
  // Sum over all vertices of the force the pins exert on the cloth, N.
  PetscErrorCode pin_reaction(Vec x, Eigen::Vector3d* reaction);

  // Lumped vertex masses (areal density x area / 3 from each triangle; unit
  // density when the cloth has none) on the free dofs, kg.
  PetscErrorCode lumped_mass(Vec mass);

  // A force typical of the membrane, N: the largest initial modulus times the
  // square root of the material area. Residuals below ~1e-12 of it are round-off.
  double force_scale() const;

  PetscInt owned_triangle_count() const { return PetscInt(triangles_.size()); }
  PetscInt global_dof_count() const { return global_dofs_; }

private:
  struct LocalTriangle {
    std::array<PetscInt, 9> dofs; // local-vector indices, corner by corner
    element::TriangleRest rest;
    int index; // in the mesh
  };
  struct LocalHinge {
    std::array<PetscInt, 12> dofs;
    element::HingeRest rest;
  };

  PetscErrorCode to_local(Vec x);
  template <typename Visit>
  PetscErrorCode for_each_triangle(const Visit& visit) const;

  MPI_Comm comm_;
  const TriangleMesh& mesh_;
  ClothMaterial material_;
  std::vector<int> pinned_;
  DM dm_ = nullptr;
  Vec local_x_ = nullptr;
  Vec local_f_ = nullptr;
  PetscInt global_dofs_ = 0;
  std::vector<PetscInt> vertex_dof_; // local-vector offset of each mesh vertex, -1 if absent
  std::vector<bool> vertex_owned_;   // this rank owns the vertex (for point forces, outputs)
  std::vector<LocalTriangle> triangles_;
  std::vector<LocalHinge> hinges_;
  std::vector<Eigen::Vector3d> pin_positions_;
};

} // namespace sartor
