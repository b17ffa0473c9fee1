#include "fem/block_assembly.hpp"

#include <petscdm.h>

#include <algorithm>
#include <cstring>

namespace sartor::fem {

namespace {

constexpr PetscInt block_size = 3;

PetscErrorCode record_values(Mat recording, PetscInt rows, const PetscInt* row_dofs,
                             PetscInt columns, const PetscInt* column_dofs, const PetscScalar*,
                             InsertMode) {
  void* context = nullptr;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(recording, &context));
  static_cast<BlockPattern*>(context)->add_global(rows, row_dofs, columns, column_dofs);
  PetscFunctionReturn(0);
}

// Sorts and de-duplicates each row of a CSR structure in place.
void compress_rows(std::vector<PetscInt>* offsets, std::vector<PetscInt>* columns) {
  PetscInt kept = 0;
  const std::size_t rows = offsets->size() - 1;
  PetscInt begin = (*offsets)[0];
  for (std::size_t r = 0; r < rows; ++r) {
    const PetscInt end = (*offsets)[r + 1];
    auto* first = columns->data() + begin;
    std::sort(first, columns->data() + end);
    const auto* last = std::unique(first, columns->data() + end);
    const auto count = PetscInt(last - first);
    std::memmove(columns->data() + kept, first, std::size_t(count) * sizeof(PetscInt));
    (*offsets)[r] = kept;
    kept += count;
    begin = end;
  }
  offsets->back() = kept;
  columns->resize(std::size_t(kept));
}

// Every rank sends the (row, column) pairs in outgoing[r] to rank r (and
// empties them); *incoming gets the pairs the other ranks send it.
PetscErrorCode exchange_pairs(MPI_Comm comm, PetscMPIInt ranks,
                              std::vector<std::vector<PetscInt>>& outgoing,
                              std::vector<PetscInt>* incoming) {
  PetscFunctionBeginUser;
  std::vector<PetscMPIInt> send_counts(static_cast<std::size_t>(ranks), 0);
  std::vector<PetscMPIInt> receive_counts(static_cast<std::size_t>(ranks), 0);
  std::vector<PetscMPIInt> send_offsets(std::size_t(ranks) + 1, 0),
      receive_offsets(std::size_t(ranks) + 1, 0);
  std::vector<PetscInt> buffer;
  for (std::size_t r = 0; r < std::size_t(ranks); ++r) {
    send_counts[r] = PetscMPIInt(outgoing[r].size());
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
    buffer.insert(buffer.end(), outgoing[r].begin(), outgoing[r].end());
    outgoing[r] = {};
  }
  PetscCallMPI(
      MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm));
  for (std::size_t r = 0; r < std::size_t(ranks); ++r)
    receive_offsets[r + 1] = receive_offsets[r] + receive_counts[r];
  incoming->resize(std::size_t(receive_offsets.back()));
  PetscCallMPI(MPI_Alltoallv(buffer.data(), send_counts.data(), send_offsets.data(), MPIU_INT,
                             incoming->data(), receive_counts.data(), receive_offsets.data(),
                             MPIU_INT, comm));
  PetscFunctionReturn(0);
}

// Preallocates J from the block CSR structure of the owned block rows
// [begin, end): exactly for AIJ, by counts per block row for the other types.
PetscErrorCode set_preallocation(Mat J, PetscInt begin, PetscInt end,
                                 const std::vector<PetscInt>& offsets,
                                 const std::vector<PetscInt>& columns) {
  PetscFunctionBeginUser;
  const auto owned = std::size_t(end - begin);
  PetscBool seq_aij = PETSC_FALSE, mpi_aij = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATSEQAIJ, &seq_aij));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATMPIAIJ, &mpi_aij));
  if (seq_aij || mpi_aij) {
    // The scalar structure: every block expands to 3 x 3 entries.
    std::vector<PetscInt> rows(block_size * owned + 1, 0), entries;
    entries.reserve(std::size_t(block_size * block_size) * columns.size());
    for (std::size_t r = 0; r < owned; ++r) {
      for (PetscInt a = 0; a < block_size; ++a) {
        for (PetscInt k = offsets[r]; k < offsets[r + 1]; ++k)
          for (PetscInt b = 0; b < block_size; ++b)
            entries.push_back(block_size * columns[std::size_t(k)] + b);
        rows[block_size * r + std::size_t(a) + 1] = PetscInt(entries.size());
      }
    }
    if (seq_aij) PetscCall(MatSeqAIJSetPreallocationCSR(J, rows.data(), entries.data(), nullptr));
    if (mpi_aij) PetscCall(MatMPIAIJSetPreallocationCSR(J, rows.data(), entries.data(), nullptr));
    PetscFunctionReturn(0);
  }
  // Other types (BAIJ, SBAIJ, ...): exact counts per block row.
  std::vector<PetscInt> diagonal(owned, 0), off(owned, 0), upper_diagonal(owned, 0),
      upper_off(owned, 0);
  for (std::size_t r = 0; r < owned; ++r) {
    const PetscInt row = begin + PetscInt(r);
    for (PetscInt k = offsets[r]; k < offsets[r + 1]; ++k) {
      const PetscInt column = columns[std::size_t(k)];
      const bool local = column >= begin && column < end;
      (local ? diagonal : off)[r] += 1;
      if (column >= row) (local ? upper_diagonal : upper_off)[r] += 1;
    }
  }
  PetscCall(MatXAIJSetPreallocation(J, block_size, diagonal.data(), off.data(),
                                    upper_diagonal.data(), upper_off.data()));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode block_layout(DM dm, BlockLayout* layout) {
  ISLocalToGlobalMapping map = nullptr;
  PetscInt local_dofs = 0, begin = 0, end = 0;
  const PetscInt* global = nullptr;
  Vec vector = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm, &vector));
  PetscCall(VecGetOwnershipRange(vector, &begin, &end));
  PetscCall(DMRestoreGlobalVector(dm, &vector));
  layout->owned_begin = begin / block_size;
  layout->owned_end = end / block_size;
  PetscCall(DMGetLocalToGlobalMapping(dm, &map));
  PetscCall(ISLocalToGlobalMappingGetSize(map, &local_dofs));
  PetscCall(ISLocalToGlobalMappingGetIndices(map, &global));
  layout->global_block.resize(std::size_t(local_dofs / block_size));
  // Constrained dofs map to negative indices.
  for (std::size_t b = 0; b < layout->global_block.size(); ++b) {
    const PetscInt first = global[block_size * PetscInt(b)];
    layout->global_block[b] = first < 0 ? -1 : first / block_size;
  }
  PetscCall(ISLocalToGlobalMappingRestoreIndices(map, &global));
  PetscFunctionReturn(0);
}

BlockPattern::BlockPattern(MPI_Comm comm, const BlockLayout& layout)
    : comm_(comm), layout_(layout) {
  element_ends_.push_back(0);
}

BlockPattern::~BlockPattern() {
  MatDestroy(&recorder_);
}

void BlockPattern::add_global(PetscInt rows, const PetscInt* row_dofs, PetscInt columns,
                              const PetscInt* column_dofs) {
  for (PetscInt i = 0; i < rows; ++i) {
    if (row_dofs[i] < 0) continue;
    for (PetscInt j = 0; j < columns; ++j) {
      if (column_dofs[j] >= 0)
        pairs_.push_back({row_dofs[i] / block_size, column_dofs[j] / block_size});
    }
  }
}

PetscErrorCode BlockPattern::recorder(Mat* recording) {
  PetscInt local_rows = block_size * (layout_.owned_end - layout_.owned_begin);
  PetscFunctionBeginUser;
  if (!recorder_) {
    PetscCall(MatCreateShell(comm_, local_rows, local_rows, PETSC_DETERMINE, PETSC_DETERMINE, this,
                             &recorder_));
    PetscCall(MatShellSetOperation(recorder_, MATOP_SET_VALUES,
                                   reinterpret_cast<void (*)(void)>(record_values)));
  }
  *recording = recorder_;
  PetscFunctionReturn(0);
}

PetscErrorCode BlockPattern::preallocate(Mat J) {
  PetscMPIInt ranks = 1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &ranks));
  const PetscInt begin = layout_.owned_begin;
  const auto owned = std::size_t(layout_.owned_end - begin);
  const auto is_owned = [&](PetscInt block) { return block >= begin && block < layout_.owned_end; };

  // Couplings of rows owned elsewhere go to their owners as (row, column) pairs.
  std::vector<PetscInt> block_ranges(std::size_t(ranks) + 1, 0);
  PetscCallMPI(
      MPI_Allgather(&layout_.owned_end, 1, MPIU_INT, block_ranges.data() + 1, 1, MPIU_INT, comm_));
  std::vector<std::vector<PetscInt>> outgoing(static_cast<std::size_t>(ranks));
  const auto send = [&](PetscInt row, PetscInt column) {
    const auto owner = std::size_t(std::upper_bound(block_ranges.begin(), block_ranges.end(), row) -
                                   block_ranges.begin() - 1);
    outgoing[owner].insert(outgoing[owner].end(), {row, column});
  };

  // Counts per owned row (an upper bound: duplicates are removed later).
  // Every free vertex keeps its diagonal block (damping and contact add to it).
  std::vector<PetscInt> offsets(owned + 1, 1);
  offsets[0] = 0;
  for (std::size_t e = 0; e + 1 < element_ends_.size(); ++e) {
    const PetscInt* blocks = element_blocks_.data() + element_ends_[e];
    const auto vertices = PetscInt(element_ends_[e + 1] - element_ends_[e]);
    for (PetscInt i = 0; i < vertices; ++i) {
      if (blocks[i] < 0) continue;
      if (is_owned(blocks[i])) {
        offsets[std::size_t(blocks[i] - begin) + 1] += vertices;
      } else {
        for (PetscInt j = 0; j < vertices; ++j)
          if (blocks[j] >= 0) send(blocks[i], blocks[j]);
      }
    }
  }
  for (const auto& [row, column] : pairs_) {
    if (is_owned(row))
      ++offsets[std::size_t(row - begin) + 1];
    else
      send(row, column);
  }

  std::vector<PetscInt> incoming;
  if (ranks > 1) {
    PetscCall(exchange_pairs(comm_, ranks, outgoing, &incoming));
    for (std::size_t k = 0; k < incoming.size(); k += 2)
      ++offsets[std::size_t(incoming[k] - begin) + 1];
  }

  // Fill, then sort and de-duplicate every row.
  for (std::size_t r = 0; r < owned; ++r)
    offsets[r + 1] += offsets[r];
  std::vector<PetscInt> columns(std::size_t(offsets.back()));
  std::vector<PetscInt> fill(offsets.begin(), offsets.end() - 1);
  const auto put = [&](PetscInt row, PetscInt column) {
    columns[std::size_t(fill[std::size_t(row - begin)]++)] = column;
  };
  for (std::size_t r = 0; r < owned; ++r)
    put(begin + PetscInt(r), begin + PetscInt(r));
  for (std::size_t e = 0; e + 1 < element_ends_.size(); ++e) {
    const PetscInt* blocks = element_blocks_.data() + element_ends_[e];
    const auto vertices = PetscInt(element_ends_[e + 1] - element_ends_[e]);
    for (PetscInt i = 0; i < vertices; ++i) {
      if (blocks[i] < 0 || !is_owned(blocks[i])) continue;
      for (PetscInt j = 0; j < vertices; ++j) {
        // A pinned column still takes its slot in the count; it is dropped
        // below with the duplicates by pointing it at the diagonal.
        put(blocks[i], blocks[j] >= 0 ? blocks[j] : blocks[i]);
      }
    }
  }
  for (const auto& [row, column] : pairs_)
    if (is_owned(row)) put(row, column);
  for (std::size_t k = 0; k < incoming.size(); k += 2)
    put(incoming[k], incoming[k + 1]);
  compress_rows(&offsets, &columns);

  PetscCall(set_preallocation(J, begin, layout_.owned_end, offsets, columns));
  PetscFunctionReturn(0);
}

PetscErrorCode ElementScatter::attach(Mat J) {
  PetscBool mpi_aij = PETSC_FALSE;
  PetscInt begin = 0, end = 0;
  PetscFunctionBeginUser;
  J_ = J;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATMPIAIJ, &mpi_aij));
  if (mpi_aij) {
    PetscCall(MatMPIAIJGetSeqAIJ(J, &diagonal_, &off_diagonal_, &off_columns_));
  } else {
    diagonal_ = J;
  }
  PetscCall(MatGetOwnershipRange(J, &begin, &end));
  row_begin_ = begin / block_size;
  row_end_ = end / block_size;
  PetscFunctionReturn(0);
}

PetscErrorCode ElementScatter::locate(const PetscInt* dofs, int vertices) {
  const PetscInt *rows = nullptr, *columns = nullptr, *off_rows = nullptr, *off_columns = nullptr;
  PetscInt count = 0;
  PetscBool done = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(MatGetRowIJ(diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &rows, &columns, &done));
  if (off_diagonal_) {
    PetscCall(MatGetRowIJ(off_diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &off_rows,
                          &off_columns, &done));
  }
  const std::size_t first = global_block_.size();
  for (int i = 0; i < vertices; ++i)
    global_block_.push_back(global_block_of_local_[std::size_t(dofs[3 * i] / block_size)]);
  for (int i = 0; i < vertices; ++i) {
    const PetscInt row_block = global_block_[first + std::size_t(i)];
    const bool owned = row_block >= row_begin_ && row_block < row_end_;
    for (int j = 0; j < vertices; ++j) {
      const PetscInt column_block = global_block_[first + std::size_t(j)];
      if (!owned || column_block < 0) {
        position_.push_back(-1);
        continue;
      }
      const PetscInt row = block_size * (row_block - row_begin_);
      const PetscInt column = block_size * column_block;
      PetscInt found = -1;
      if (column_block >= row_begin_ && column_block < row_end_) {
        // Square matrix: the diagonal part's columns are the owned rows.
        const PetscInt* at = std::lower_bound(columns + rows[row], columns + rows[row + 1],
                                              column - block_size * row_begin_);
        if (at != columns + rows[row + 1] && *at == column - block_size * row_begin_)
          found = PetscInt(at - (columns + rows[row]));
      } else if (off_diagonal_) {
        const PetscInt* at = std::lower_bound(
            off_columns + off_rows[row], off_columns + off_rows[row + 1], column,
            [this](PetscInt local, PetscInt global) { return off_columns_[local] < global; });
        if (at != off_columns + off_rows[row + 1] && off_columns_[*at] == column)
          found = -(PetscInt(at - (off_columns + off_rows[row])) + 2);
      }
      PetscCheck(found != -1, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "element block (%" PetscInt_FMT ", %" PetscInt_FMT
                 ") is not in the preallocated Jacobian",
                 row_block, column_block);
      position_.push_back(found);
    }
  }
  PetscCall(
      MatRestoreRowIJ(diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &rows, &columns, &done));
  if (off_diagonal_) {
    PetscCall(MatRestoreRowIJ(off_diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &off_rows,
                              &off_columns, &done));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ElementScatter::begin() {
  PetscInt count = 0;
  PetscBool done = PETSC_FALSE;
  const PetscInt* columns = nullptr;
  PetscFunctionBeginUser;
  vertex_cursor_ = 0;
  block_cursor_ = 0;
  PetscCall(MatGetRowIJ(diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &diagonal_rows_, &columns,
                        &done));
  PetscCall(MatSeqAIJGetArray(diagonal_, &diagonal_values_));
  if (off_diagonal_) {
    PetscCall(MatGetRowIJ(off_diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &off_rows_, &columns,
                          &done));
    PetscCall(MatSeqAIJGetArray(off_diagonal_, &off_values_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ElementScatter::add_values(const double* column_major, int vertices) {
  const auto n = std::size_t(block_size) * std::size_t(vertices);
  const PetscInt* blocks = global_block_.data() + vertex_cursor_;
  const PetscInt* position = position_.data() + block_cursor_;
  PetscFunctionBeginUser;
  vertex_cursor_ += std::size_t(vertices);
  block_cursor_ += std::size_t(vertices * vertices);
  bool foreign = false;
  for (int i = 0; i < vertices; ++i) {
    const PetscInt row_block = blocks[i];
    if (row_block < 0) continue;
    if (row_block < row_begin_ || row_block >= row_end_) {
      foreign = true;
      continue;
    }
    const PetscInt row = block_size * (row_block - row_begin_);
    for (int j = 0; j < vertices; ++j) {
      const PetscInt at = position[i * vertices + j];
      if (at == -1) continue;
      const bool diagonal = at >= 0;
      const PetscInt* rows = diagonal ? diagonal_rows_ : off_rows_;
      PetscScalar* values = diagonal ? diagonal_values_ : off_values_;
      const PetscInt offset = diagonal ? at : -at - 2;
      for (PetscInt a = 0; a < block_size; ++a) {
        PetscScalar* target = values + rows[row + a] + offset;
        const double* source =
            column_major + std::size_t(block_size * j) * n + std::size_t(block_size * i + a);
        for (std::size_t b = 0; b < std::size_t(block_size); ++b)
          target[b] += source[b * n];
      }
    }
  }
  if (!foreign) PetscFunctionReturn(0);
  // Rows of another rank's vertices: through the assembly stash, which
  // leaves this rank's arrays alone.
  columns_.clear();
  for (int j = 0; j < vertices; ++j)
    for (PetscInt b = 0; b < block_size; ++b)
      columns_.push_back(blocks[j] < 0 ? -1 : block_size * blocks[j] + b);
  for (int i = 0; i < vertices; ++i) {
    const PetscInt row_block = blocks[i];
    if (row_block < 0 || (row_block >= row_begin_ && row_block < row_end_)) continue;
    foreign_rows_.clear();
    foreign_values_.clear();
    for (PetscInt a = 0; a < block_size; ++a) {
      foreign_rows_.push_back(block_size * row_block + a);
      for (std::size_t c = 0; c < n; ++c)
        foreign_values_.push_back(column_major[c * n + std::size_t(block_size * i + a)]);
    }
    PetscCall(MatSetValues(J_, block_size, foreign_rows_.data(), PetscInt(n), columns_.data(),
                           foreign_values_.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ElementScatter::end() {
  PetscInt count = 0;
  PetscBool done = PETSC_FALSE;
  const PetscInt* columns = nullptr;
  PetscFunctionBeginUser;
  PetscCall(MatSeqAIJRestoreArray(diagonal_, &diagonal_values_));
  PetscCall(MatRestoreRowIJ(diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &diagonal_rows_,
                            &columns, &done));
  if (off_diagonal_) {
    PetscCall(MatSeqAIJRestoreArray(off_diagonal_, &off_values_));
    PetscCall(MatRestoreRowIJ(off_diagonal_, 0, PETSC_FALSE, PETSC_FALSE, &count, &off_rows_,
                              &columns, &done));
  }
  PetscFunctionReturn(0);
}

} // namespace sartor::fem
