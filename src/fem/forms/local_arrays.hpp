#pragma once
// Gathering element values from, and adding them to, the arrays of a local
// (ghosted) vector with three dofs per vertex.

#include <petscsys.h>

#include <Eigen/Core>

#include <array>

namespace sartor::fem {

template <int N>
Eigen::Matrix<double, N, 1> gather(const PetscScalar* x, const std::array<PetscInt, N>& dofs) {
  Eigen::Matrix<double, N, 1> values;
  for (int i = 0; i < N; ++i)
    values[i] = x[dofs[std::size_t(i)]];
  return values;
}

template <int N>
void scatter_add(PetscScalar* f, const std::array<PetscInt, N>& dofs,
                 const Eigen::Matrix<double, N, 1>& values) {
  for (int i = 0; i < N; ++i)
    f[dofs[std::size_t(i)]] += values[i];
}

inline Eigen::Vector3d vertex_position(const PetscScalar* x, PetscInt offset) {
  return {x[offset], x[offset + 1], x[offset + 2]};
}

} // namespace sartor::fem
