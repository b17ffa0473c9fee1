#include "fem/mesh_partition.hpp"

#include <metis.h>

#include <algorithm>
#include <map>
#include <utility>

namespace sartor {

namespace {

std::vector<int> contiguous_parts(std::size_t triangles, int parts) {
  std::vector<int> part(triangles);
  for (std::size_t t = 0; t < triangles; ++t)
    part[t] = int(t * std::size_t(parts) / std::max<std::size_t>(triangles, 1));
  return part;
}

// Compressed adjacency of the triangles that share an edge.
void triangle_graph(const TriangleMesh& mesh, std::vector<idx_t>* offsets,
                    std::vector<idx_t>* neighbours) {
  std::map<std::pair<int, int>, std::vector<idx_t>> edge_triangles;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      edge_triangles[{std::min(a, b), std::max(a, b)}].push_back(idx_t(t));
    }
  std::vector<std::vector<idx_t>> adjacent(mesh.triangle_count());
  for (const auto& [edge, triangles] : edge_triangles)
    for (idx_t s : triangles)
      for (idx_t t : triangles)
        if (s != t) adjacent[std::size_t(s)].push_back(t);
  offsets->assign(1, 0);
  neighbours->clear();
  for (const auto& list : adjacent) {
    neighbours->insert(neighbours->end(), list.begin(), list.end());
    offsets->push_back(idx_t(neighbours->size()));
  }
}

} // namespace

std::vector<int> partition_triangles(const TriangleMesh& mesh, int parts) {
  const std::size_t triangles = mesh.triangle_count();
  if (parts <= 1 || triangles < 2 * std::size_t(parts)) return contiguous_parts(triangles, parts);
  std::vector<idx_t> offsets, neighbours;
  triangle_graph(mesh, &offsets, &neighbours);
  idx_t vertices = idx_t(triangles), constraints = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(triangles, 0);
  const int status =
      METIS_PartGraphKway(&vertices, &constraints, offsets.data(), neighbours.data(), nullptr,
                          nullptr, nullptr, &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK) return contiguous_parts(triangles, parts);
  return std::vector<int>(part.begin(), part.end());
}

PetscErrorCode set_default_partition(PetscPartitioner partitioner, MPI_Comm comm,
                                     const TriangleMesh& mesh) {
  PetscMPIInt size = 1, rank = 0;
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-petscpartitioner_type", &chosen));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (chosen || size == 1) PetscFunctionReturn(0);
  std::vector<PetscInt> sizes(std::size_t(size), 0), points;
  if (rank == 0) {
    const std::vector<int> part = partition_triangles(mesh, size);
    for (int p : part)
      ++sizes[std::size_t(p)];
    for (int p = 0; p < size; ++p)
      for (std::size_t t = 0; t < part.size(); ++t)
        if (part[t] == p) points.push_back(PetscInt(t));
  }
  PetscCall(PetscPartitionerSetType(partitioner, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(partitioner, size, sizes.data(), points.data()));
  PetscFunctionReturn(0);
}

} // namespace sartor
