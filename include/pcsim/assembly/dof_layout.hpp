// Distribution of a (replicated) catenary mesh over the ranks of a
// communicator.
//
// The node graph is partitioned with METIS; every rank owns a set of nodes and
// numbers the free DOFs of its nodes contiguously (PETSc ownership ranges).
// Constrained DOFs have no equation (global index -1: PETSc ignores negative
// indices in VecSetValues/MatSetValues). Elements are assembled by the owner
// of their first node. "Extra" global unknowns (form-finding parameters,
// pantograph DOFs) are appended after the catenary DOFs and owned by the last
// rank. Each rank gathers the values of the nodes its elements touch (owned +
// ghost) with one VecScatter.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::assembly {

class DofLayout {
 public:
  // node_owner: a partition of the nodes computed before (same mesh graph),
  // reused instead of calling METIS again; null: partition with METIS.
  DofLayout(MPI_Comm comm, const catenary::CatenaryMesh& mesh, PetscInt extra_dofs = 0,
            const std::vector<int>* node_owner = nullptr);
  ~DofLayout();
  DofLayout(const DofLayout&) = delete;
  DofLayout& operator=(const DofLayout&) = delete;

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

  // Global equation number of DOF c (0..5) of node n, -1 if constrained.
  PetscInt global_dof(int node, int c) const { return node_dofs_[6 * node + c]; }
  int owner(int node) const { return owner_[node]; }
  const std::vector<int>& node_owner() const { return owner_; }
  PetscInt catenary_dofs() const { return n_catenary_; }  // global, free catenary DOFs
  PetscInt extra_dofs() const { return n_extra_; }
  PetscInt extra_global(PetscInt k) const { return n_catenary_ + k; }
  PetscInt global_size() const { return n_catenary_ + n_extra_; }
  PetscInt local_size() const { return local_size_; }    // rows owned, incl. extras
  PetscInt first_owned() const { return first_owned_; }  // first owned global row

  // Elements and point items assembled on this rank.
  const std::vector<int>& local_cables() const { return local_cables_; }
  const std::vector<int>& local_bars() const { return local_bars_; }
  const std::vector<int>& local_point_masses() const { return local_point_masses_; }
  const std::vector<int>& local_springs() const { return local_springs_; }
  const std::vector<int>& owned_nodes() const { return owned_nodes_; }

  // Nodes this rank reads (owned + ghost) and, per such node and DOF, the
  // position in the gathered local array (-1: constrained, value is the design value).
  const std::vector<int>& needed_nodes() const { return needed_nodes_; }
  int needed_index(int node) const;  // index into needed_nodes(), -1 if not needed
  PetscInt gathered_size() const { return gathered_size_; }
  PetscInt gathered_position(int needed, int c) const { return gathered_pos_[6 * needed + c]; }
  // True when the gathered vector is the start of the global one (one rank,
  // nodes numbered in order): a global vector's array can be read in its place.
  bool gather_identity() const { return gather_identity_; }

  // Gathers the free catenary DOFs of the needed nodes from a global vector.
  void gather(Vec global, Vec gathered) const;
  // Adds gathered-layout values into a global vector (reverse scatter).
  void scatter_add(Vec gathered, Vec global) const;
  Vec create_gathered_vector() const;
  Vec create_global_vector() const;

  // A matrix preallocated for the element couplings, plus optional extra
  // couplings: for each extra unknown k, the nodes whose DOFs couple with it
  // (both the row of k and the column of k in those node rows), and whether
  // the extra rows couple with each other (dense extra block).
  Mat create_matrix(const std::vector<std::vector<int>>& extra_node_couplings = {},
                    bool dense_extra_block = false) const;

  // Nodes adjacent to each node through any element (including itself), sorted.
  const std::vector<std::vector<int>>& node_adjacency() const { return adjacency_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  PetscInt n_catenary_ = 0, n_extra_ = 0, local_size_ = 0, first_owned_ = 0;
  std::vector<int> owner_;
  std::vector<PetscInt> node_dofs_;
  std::vector<int> local_cables_, local_bars_, local_point_masses_, local_springs_;
  std::vector<int> owned_nodes_, needed_nodes_, needed_lookup_;
  std::vector<PetscInt> gathered_pos_;
  PetscInt gathered_size_ = 0;
  bool gather_identity_ = false;
  std::vector<std::vector<int>> adjacency_;
  VecScatter scatter_ = nullptr;
  Vec scatter_template_global_ = nullptr, scatter_template_local_ = nullptr;
};

// True when a cable element touches the node (its slope DOFs are unknowns).
std::vector<bool> nodes_with_slopes(const catenary::CatenaryMesh& mesh);

}  // namespace pcsim::assembly
