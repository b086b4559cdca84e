#include "pcsim/assembly/dof_layout.hpp"

#include <metis.h>

#include <algorithm>
#include <numeric>

#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

using catenary::CatenaryMesh;

std::vector<bool> nodes_with_slopes(const CatenaryMesh& mesh) {
  std::vector<bool> has(mesh.nodes.size(), false);
  for (const auto& e : mesh.cables) has[e.nodes[0]] = has[e.nodes[1]] = true;
  return has;
}

namespace {

std::vector<std::vector<int>> build_adjacency(const CatenaryMesh& mesh) {
  std::vector<std::vector<int>> adj(mesh.nodes.size());
  for (std::size_t n = 0; n < adj.size(); ++n) adj[n].push_back(static_cast<int>(n));
  auto link = [&](int a, int b) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  };
  for (const auto& e : mesh.cables) link(e.nodes[0], e.nodes[1]);
  for (const auto& b : mesh.bars) link(b.nodes[0], b.nodes[1]);
  for (auto& list : adj) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adj;
}

// METIS k-way partition of the node graph, computed on rank 0 and broadcast
// so that every rank holds the same partition.
std::vector<int> partition_nodes(MPI_Comm comm, int size,
                                 const std::vector<std::vector<int>>& adjacency) {
  const idx_t n = static_cast<idx_t>(adjacency.size());
  std::vector<int> owner(adjacency.size(), 0);
  if (size == 1 || n == 0) return owner;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    std::vector<idx_t> xadj(n + 1, 0), adjncy;
    for (idx_t i = 0; i < n; ++i) {
      for (int j : adjacency[i])
        if (j != i) adjncy.push_back(j);
      xadj[i + 1] = static_cast<idx_t>(adjncy.size());
    }
    idx_t ncon = 1, nparts = size, objval = 0;
    std::vector<idx_t> part(n, 0);
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 7;
    int status = n > size ? METIS_PartGraphKway(&const_cast<idx_t&>(n), &ncon, xadj.data(),
                                                adjncy.data(), nullptr, nullptr, nullptr, &nparts,
                                                nullptr, nullptr, options, &objval, part.data())
                          : METIS_OK;
    if (status != METIS_OK) throw SolverError("METIS partitioning failed");
    if (n <= size)
      for (idx_t i = 0; i < n; ++i) part[i] = i % size;
    for (idx_t i = 0; i < n; ++i) owner[i] = static_cast<int>(part[i]);
  }
  MPI_Bcast(owner.data(), static_cast<int>(n), MPI_INT, 0, comm);
  return owner;
}

}  // namespace

DofLayout::DofLayout(MPI_Comm comm, const CatenaryMesh& mesh, PetscInt extra_dofs,
                     const std::vector<int>* node_owner)
    : comm_(comm), n_extra_(extra_dofs) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  adjacency_ = build_adjacency(mesh);
  if (node_owner && node_owner->size() == mesh.nodes.size() &&
      std::all_of(node_owner->begin(), node_owner->end(), [&](int r) { return r < size_; }))
    owner_ = *node_owner;
  else
    owner_ = partition_nodes(comm_, size_, adjacency_);

  // Free DOFs: not fixed in the design; slope DOFs only on cable nodes.
  const auto has_slope = nodes_with_slopes(mesh);
  auto is_free = [&](int n, int c) {
    if (mesh.nodes[n].fixed[c]) return false;
    return c < 3 || has_slope[n];
  };
  // Number the free DOFs rank by rank, nodes in increasing index: identical on
  // every rank, no communication needed.
  node_dofs_.assign(6 * static_cast<std::size_t>(n_nodes), -1);
  std::vector<std::vector<int>> nodes_of_rank(size_);
  for (int n = 0; n < n_nodes; ++n) nodes_of_rank[owner_[n]].push_back(n);
  PetscInt next = 0;
  for (int r = 0; r < size_; ++r) {
    if (r == rank_) first_owned_ = next;
    for (int n : nodes_of_rank[r])
      for (int c = 0; c < 6; ++c)
        if (is_free(n, c)) node_dofs_[6 * n + c] = next++;
    if (r == rank_) local_size_ = next - first_owned_;
  }
  n_catenary_ = next;
  if (rank_ == size_ - 1) local_size_ += n_extra_;
  owned_nodes_ = nodes_of_rank[rank_];

  // Local elements: assembled by the owner of their first node.
  for (std::size_t e = 0; e < mesh.cables.size(); ++e)
    if (owner_[mesh.cables[e].nodes[0]] == rank_) local_cables_.push_back(static_cast<int>(e));
  for (std::size_t e = 0; e < mesh.bars.size(); ++e)
    if (owner_[mesh.bars[e].nodes[0]] == rank_) local_bars_.push_back(static_cast<int>(e));
  for (std::size_t i = 0; i < mesh.point_masses.size(); ++i)
    if (owner_[mesh.point_masses[i].node] == rank_)
      local_point_masses_.push_back(static_cast<int>(i));
  for (std::size_t i = 0; i < mesh.springs.size(); ++i)
    if (owner_[mesh.springs[i].node] == rank_) local_springs_.push_back(static_cast<int>(i));

  // Needed nodes: owned ones and every node of a local element.
  std::vector<char> needed(n_nodes, 0);
  for (int n : owned_nodes_) needed[n] = 1;
  for (int e : local_cables_) needed[mesh.cables[e].nodes[0]] = needed[mesh.cables[e].nodes[1]] = 1;
  for (int e : local_bars_) needed[mesh.bars[e].nodes[0]] = needed[mesh.bars[e].nodes[1]] = 1;
  needed_lookup_.assign(n_nodes, -1);
  std::vector<PetscInt> from;
  for (int n = 0; n < n_nodes; ++n) {
    if (!needed[n]) continue;
    needed_lookup_[n] = static_cast<int>(needed_nodes_.size());
    needed_nodes_.push_back(n);
    for (int c = 0; c < 6; ++c) {
      PetscInt g = node_dofs_[6 * n + c];
      gathered_pos_.push_back(g >= 0 ? static_cast<PetscInt>(from.size()) : -1);
      if (g >= 0) from.push_back(g);
    }
  }
  gathered_size_ = static_cast<PetscInt>(from.size());
  gather_identity_ = size_ == 1;
  for (PetscInt i = 0; i < gathered_size_ && gather_identity_; ++i)
    gather_identity_ = from[static_cast<std::size_t>(i)] == i;

  PCSIM_PETSC(VecCreateMPI(comm_, local_size_, PETSC_DETERMINE, &scatter_template_global_));
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, gathered_size_, &scatter_template_local_));
  IS is_from;
  PCSIM_PETSC(
      ISCreateGeneral(PETSC_COMM_SELF, gathered_size_, from.data(), PETSC_COPY_VALUES, &is_from));
  PCSIM_PETSC(VecScatterCreate(scatter_template_global_, is_from, scatter_template_local_, nullptr,
                               &scatter_));
  PCSIM_PETSC(ISDestroy(&is_from));
}

DofLayout::~DofLayout() {
  VecScatterDestroy(&scatter_);
  VecDestroy(&scatter_template_global_);
  VecDestroy(&scatter_template_local_);
}

int DofLayout::needed_index(int node) const {
  return needed_lookup_[node];
}

void DofLayout::gather(Vec global, Vec gathered) const {
  PCSIM_PETSC(VecScatterBegin(scatter_, global, gathered, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(scatter_, global, gathered, INSERT_VALUES, SCATTER_FORWARD));
}

void DofLayout::scatter_add(Vec gathered, Vec global) const {
  PCSIM_PETSC(VecScatterBegin(scatter_, gathered, global, ADD_VALUES, SCATTER_REVERSE));
  PCSIM_PETSC(VecScatterEnd(scatter_, gathered, global, ADD_VALUES, SCATTER_REVERSE));
}

Vec DofLayout::create_gathered_vector() const {
  Vec v;
  PCSIM_PETSC(VecDuplicate(scatter_template_local_, &v));
  return v;
}

Vec DofLayout::create_global_vector() const {
  Vec v;
  PCSIM_PETSC(VecDuplicate(scatter_template_global_, &v));
  return v;
}

Mat DofLayout::create_matrix(const std::vector<std::vector<int>>& extra_node_couplings,
                             bool dense_extra_block) const {
  const bool extras_here = rank_ == size_ - 1;
  std::vector<PetscInt> d_nnz(local_size_, 0), o_nnz(local_size_, 0);
  // Node rows: every free DOF of every adjacent node.
  for (int n : owned_nodes_) {
    PetscInt d = 0, o = 0;
    for (int m : adjacency_[n])
      for (int c = 0; c < 6; ++c)
        if (node_dofs_[6 * m + c] >= 0) (owner_[m] == rank_ ? d : o)++;
    for (int c = 0; c < 6; ++c) {
      PetscInt g = node_dofs_[6 * n + c];
      if (g < 0) continue;
      d_nnz[g - first_owned_] = d;
      o_nnz[g - first_owned_] = o;
    }
  }
  // Extra couplings: column k in the rows of the listed nodes; row k over
  // the DOFs of those nodes.
  for (std::size_t k = 0; k < extra_node_couplings.size(); ++k) {
    std::vector<int> nodes = extra_node_couplings[k];
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    PetscInt row_d = 0, row_o = 0;
    for (int n : nodes) {
      for (int c = 0; c < 6; ++c) {
        PetscInt g = node_dofs_[6 * n + c];
        if (g < 0) continue;
        if (owner_[n] == rank_) (extras_here ? d_nnz : o_nnz)[g - first_owned_]++;
        (owner_[n] == size_ - 1 ? row_d : row_o)++;
      }
    }
    if (extras_here) {
      PetscInt row = n_catenary_ + static_cast<PetscInt>(k) - first_owned_;
      d_nnz[row] = row_d + (dense_extra_block ? n_extra_ : 1);
      o_nnz[row] = row_o;
    }
  }
  if (extras_here)
    for (PetscInt k = static_cast<PetscInt>(extra_node_couplings.size()); k < n_extra_; ++k)
      d_nnz[n_catenary_ + k - first_owned_] = dense_extra_block ? n_extra_ : 1;
  const PetscInt local_cols = local_size_;
  for (PetscInt i = 0; i < local_size_; ++i) {
    d_nnz[i] = std::min(d_nnz[i], local_cols);
    o_nnz[i] = std::min(o_nnz[i], global_size() - local_cols);
  }
  Mat A;
  PCSIM_PETSC(MatCreate(comm_, &A));
  PCSIM_PETSC(MatSetSizes(A, local_size_, local_size_, PETSC_DETERMINE, PETSC_DETERMINE));
  PCSIM_PETSC(MatSetType(A, MATAIJ));
  PCSIM_PETSC(MatSeqAIJSetPreallocation(A, 0, d_nnz.data()));
  PCSIM_PETSC(MatMPIAIJSetPreallocation(A, 0, d_nnz.data(), 0, o_nnz.data()));
  PCSIM_PETSC(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  return A;
}

}  // namespace pcsim::assembly
