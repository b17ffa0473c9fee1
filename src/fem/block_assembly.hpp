#pragma once
// Sparsity and fast assembly of a Jacobian with 3x3 vertex blocks.
//
// BlockPattern collects which vertices are coupled (by elements in local dof
// offsets, by anything else through a recording Mat in global indices) and
// preallocates the Jacobian exactly, without the hashing of MATPREALLOCATOR:
// per owned block row a sorted, de-duplicated list of block columns; rows
// that another rank owns are sent to it. AIJ matrices receive their whole
// nonzero structure (MatXAIJSetPreallocation counts for any other type).
//
// ElementScatter remembers, for every element, where each of its 3x3 blocks
// sits in the value arrays of an assembled SEQAIJ or MPIAIJ matrix, so that
// adding an element matrix is a plain sum with no column search. Rows owned
// by another rank go through MatSetValues (the assembly stash).

#include <petscdm.h>
#include <petscmat.h>

#include <Eigen/Core>

#include <array>
#include <memory>
#include <vector>

namespace sartor::fem {

// The vertex blocks of the local vector and their place in the global system.
struct BlockLayout {
  // Global block (first global dof / 3) of every local block (local offset / 3);
  // -1 for a pinned vertex (its dofs are constrained out of the system).
  std::vector<PetscInt> global_block;
  PetscInt owned_begin = 0; // owned global blocks: [owned_begin, owned_end)
  PetscInt owned_end = 0;
};

// Collective: the layout of a DM's local vector with 3 dofs per vertex.
PetscErrorCode block_layout(DM dm, BlockLayout* layout);

class BlockPattern {
public:
  explicit BlockPattern(MPI_Comm comm, const BlockLayout& layout);
  ~BlockPattern();
  BlockPattern(const BlockPattern&) = delete;
  BlockPattern& operator=(const BlockPattern&) = delete;

  // All vertices of an element (local dof offsets, corner by corner) are coupled.
  template <std::size_t N>
  void add_element(const std::array<PetscInt, N>& dofs) {
    static_assert(N % 3 == 0, "three dofs per vertex");
    for (std::size_t k = 0; k < N; k += 3)
      element_blocks_.push_back(layout_.global_block[std::size_t(dofs[k] / 3)]);
    element_ends_.push_back(element_blocks_.size());
  }
  // A Mat that records every MatSetValues(Local) into it as couplings, for
  // terms assembled in global indices on any rank (seams). Owned here.
  PetscErrorCode recorder(Mat* recording);
  // Collective: preallocates J (sizes, block size 3 and type already set).
  PetscErrorCode preallocate(Mat J);

  // Used by the recorder.
  void add_global(PetscInt rows, const PetscInt* row_dofs, PetscInt columns,
                  const PetscInt* column_dofs);

private:
  MPI_Comm comm_;
  const BlockLayout& layout_;
  std::vector<PetscInt> element_blocks_;       // global blocks of the elements' vertices
  std::vector<std::size_t> element_ends_;      // end of each element in element_blocks_
  std::vector<std::array<PetscInt, 2>> pairs_; // further (row, column) global blocks
  Mat recorder_ = nullptr;
};

class ElementScatter {
public:
  explicit ElementScatter(const BlockLayout& layout)
      : global_block_of_local_(layout.global_block) {}
  // Collective: J is a SEQAIJ or MPIAIJ matrix with its final nonzero
  // structure (preallocated by BlockPattern); its layout is the one given.
  PetscErrorCode attach(Mat J);
  // Setup, in assembly order: the element's local dof offsets, corner by corner.
  template <std::size_t N>
  PetscErrorCode add_element(const std::array<PetscInt, N>& dofs) {
    static_assert(N % 3 == 0, "three dofs per vertex");
    return locate(dofs.data(), int(N / 3));
  }

  // Assembly into the attached matrix: begin, add every element's matrix in
  // setup order, end (before MatAssemblyBegin).
  PetscErrorCode begin();
  template <int N>
  PetscErrorCode add(const Eigen::Matrix<double, N, N>& matrix) {
    return add_values(matrix.data(), N / 3);
  }
  PetscErrorCode end();

private:
  PetscErrorCode locate(const PetscInt* dofs, int vertices);
  PetscErrorCode add_values(const double* column_major, int vertices);

  std::vector<PetscInt> global_block_of_local_; // as BlockLayout::global_block
  Mat J_ = nullptr;
  Mat diagonal_ = nullptr, off_diagonal_ = nullptr; // parts of the owned rows
  const PetscInt* off_columns_ = nullptr;           // global column of each off-diagonal column
  PetscInt row_begin_ = 0, row_end_ = 0;            // owned global blocks
  // Per element vertex: the global block (-1 pinned) and whether its rows are owned.
  std::vector<PetscInt> global_block_;
  // Per element block (row-major over the element's vertices), where the 3x3
  // block starts in each of its rows: >= 0 in the diagonal part, -(k + 2) at
  // offset k in the off-diagonal part, -1 for none (pinned column, row owned
  // by another rank).
  std::vector<PetscInt> position_;
  // Assembly state: next element's first vertex and block; the parts' arrays.
  std::size_t vertex_cursor_ = 0, block_cursor_ = 0;
  const PetscInt *diagonal_rows_ = nullptr, *off_rows_ = nullptr;
  PetscScalar *diagonal_values_ = nullptr, *off_values_ = nullptr;
  std::vector<PetscInt> foreign_rows_, columns_;
  std::vector<PetscScalar> foreign_values_;
};

} // namespace sartor::fem
