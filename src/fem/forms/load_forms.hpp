#pragma once
// The external loads, scaled by the load factor: gravity on the triangles'
// lumped masses and follower pressure on their current areas (a triangle
// form), and point forces on vertices. Their potentials are measured from
// the initial placement: a line search compares energies that differ by
// |F|^2/k near the solution, and g.x itself (~ weight x height) would bury
// that in round-off long before the residual is small. Pressure follows the
// surface; it has a potential, -p times the volume the surface sweeps, only
// when the surface's boundary is held (pinned) or it has none
// (element/pressure.hpp).

#include "fem/cloth_model.hpp"
#include "fem/form.hpp"
#include "mesh/triangle_mesh.hpp"

#include <vector>

namespace sartor::fem {

class SurfaceLoadForm final : public TriangleForm {
public:
  // `boundary_held`: every vertex on the mesh's boundary is pinned for good.
  SurfaceLoadForm(const ClothLoads& loads, const TriangleMesh& mesh, bool boundary_held);
  const char* name() const override { return "surface loads"; }
  EnergyPart part() const override { return EnergyPart::external; }
  void add_energy(const TriangleView& t, const FormPoint& at, double* sum) const override;
  element::Vector9 gradient(const TriangleView& t, const FormPoint& at) const override;
  void add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const override;
  bool has_potential() const override { return loads_.pressure == 0.0 || boundary_held_; }
  // Gravity's, through the lumped masses; pressure acts on the current area.
  bool has_rest_derivative() const override { return true; }
  element::Vector9 rest_derivative(const TriangleView& t, const FormPoint& at,
                                   const std::array<Eigen::Vector2d, 3>& delta_uv) const override;

private:
  const ClothLoads& loads_;
  const TriangleMesh& mesh_;
  bool boundary_held_;
  // The volumes' common apex: the starting centroid keeps their magnitudes
  // (and round-off) at the size of the cloth, wherever it is placed.
  Eigen::Vector3d volume_centre_;
};

class PointLoadForm final : public Form {
public:
  // `vertex_dof` and `vertex_owned` are the problem's layout (ClothProblem).
  PointLoadForm(const ClothLoads& loads, const TriangleMesh& mesh,
                const std::vector<PetscInt>& vertex_dof, const std::vector<bool>& vertex_owned)
      : loads_(loads), mesh_(mesh), vertex_dof_(vertex_dof), vertex_owned_(vertex_owned) {}
  const char* name() const override { return "point loads"; }
  EnergyPart part() const override { return EnergyPart::external; }
  void add_energy(const FormPoint& at, double* sum) const override;
  void add_gradient(const FormPoint& at, PetscScalar* f) const override;
  // Point forces do not depend on the pattern.
  bool has_rest_derivative() const override { return true; }

private:
  const ClothLoads& loads_;
  const TriangleMesh& mesh_;
  const std::vector<PetscInt>& vertex_dof_;
  const std::vector<bool>& vertex_owned_;
};

} // namespace sartor::fem
