#pragma once
// The partition of the cloth's triangles over the ranks. PT-Scotch, the
// partitioner PETSc would pick here, draws random numbers that change from
// run to run: the partition changed, and with it the order of every sum
// across ranks, so reruns on the same ranks differed at round-off
// (docs/reliability.md#mpi-determinism). METIS with a fixed seed partitions
// the same mesh the same way every time.

#include "mesh/triangle_mesh.hpp"

#include <petscdmplex.h>

#include <vector>

namespace sartor {

// The part (0 .. parts-1) of every triangle: METIS's k-way partition of the
// triangles' edge-adjacency graph, fixed seed; contiguous blocks of the
// triangle order when there are fewer than two triangles per part or METIS
// fails.
std::vector<int> partition_triangles(const TriangleMesh& mesh, int parts);

// Collective. Makes `partitioner` hand rank r the triangles of part r of
// partition_triangles (`mesh` is read on rank 0, where the serial mesh
// lives), unless the options name a partitioner (-petscpartitioner_type).
PetscErrorCode set_default_partition(PetscPartitioner partitioner, MPI_Comm comm,
                                     const TriangleMesh& mesh);

} // namespace sartor
