#include "fem/forms/load_forms.hpp"

#include "element/pressure.hpp"
#include "fem/forms/local_arrays.hpp"

namespace sartor::fem {

SurfaceLoadForm::SurfaceLoadForm(const ClothLoads& loads, const TriangleMesh& mesh,
                                 bool boundary_held)
    : loads_(loads), mesh_(mesh), boundary_held_(boundary_held),
      volume_centre_(Eigen::Vector3d::Zero()) {
  for (const Eigen::Vector3d& p : mesh.positions)
    volume_centre_ += p;
  if (!mesh.positions.empty()) volume_centre_ /= double(mesh.positions.size());
}

void SurfaceLoadForm::add_energy(const TriangleView& t, const FormPoint& at, double* sum) const {
  const double mass = t.material.areal_density * t.rest.area / 3.0;
  const auto& corners = mesh_.triangles[std::size_t(t.index)];
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& start = mesh_.positions[std::size_t(corners[std::size_t(k)])];
    *sum -= at.load_factor * mass * loads_.gravity.dot(t.x.segment<3>(3 * k) - start);
  }
  if (loads_.pressure == 0.0 || !boundary_held_) return;
  element::Vector9 start;
  for (int k = 0; k < 3; ++k)
    start.segment<3>(3 * k) = mesh_.positions[std::size_t(corners[std::size_t(k)])];
  *sum -= at.load_factor * loads_.pressure *
          (element::spanned_volume(t.x, volume_centre_) -
           element::spanned_volume(start, volume_centre_));
}

element::Vector9 SurfaceLoadForm::gradient(const TriangleView& t, const FormPoint& at) const {
  element::Vector9 external = element::Vector9::Zero();
  const double mass = t.material.areal_density * t.rest.area / 3.0;
  for (int k = 0; k < 3; ++k)
    external.segment<3>(3 * k) = mass * loads_.gravity;
  if (loads_.pressure != 0.0) external += element::follower_pressure(loads_.pressure, t.x).force;
  return element::Vector9(-at.load_factor * external);
}

void SurfaceLoadForm::add_hessian(const TriangleView& t, const FormPoint& at,
                                  Matrix9& block) const {
  if (loads_.pressure == 0.0) return;
  block -= at.load_factor * element::follower_pressure(loads_.pressure, t.x).jacobian;
}

element::Vector9
SurfaceLoadForm::rest_derivative(const TriangleView& t, const FormPoint& at,
                                 const std::array<Eigen::Vector2d, 3>& delta_uv) const {
  const double mass_change =
      t.material.areal_density * element::triangle_area_derivative(t.uv, delta_uv) / 3.0;
  element::Vector9 change;
  for (int k = 0; k < 3; ++k)
    change.segment<3>(3 * k) = -at.load_factor * mass_change * loads_.gravity;
  return change;
}

void PointLoadForm::add_energy(const FormPoint& at, double* sum) const {
  for (const auto& [v, force] : loads_.point_forces) {
    if (!vertex_owned_[std::size_t(v)]) continue;
    *sum -= at.load_factor * force.dot(vertex_position(at.x, vertex_dof_[std::size_t(v)]) -
                                       mesh_.positions[std::size_t(v)]);
  }
}

void PointLoadForm::add_gradient(const FormPoint& at, PetscScalar* f) const {
  for (const auto& [v, force] : loads_.point_forces) {
    if (!vertex_owned_[std::size_t(v)]) continue;
    const PetscInt offset = vertex_dof_[std::size_t(v)];
    for (int d = 0; d < 3; ++d)
      f[offset + d] -= at.load_factor * force[d];
  }
}

} // namespace sartor::fem
