// Parallel assembly of the catenary finite-element model.
//
// A CatenarySystem owns the (replicated) mesh and its distribution
// (DofLayout). It evaluates, for a global state vector of free DOFs,
//   R = f_elastic(q) - f_gravity + f_springs      (thesis eq. 3.5)
//   K_T = dR/dq                                  (thesis eq. 3.7)
// and assembles the constant mass matrix. Elements never know which solver
// calls them: statics, form-finding, modes and time integration all come
// through these functions.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pcsim/assembly/dof_layout.hpp"
#include "pcsim/catenary/mesh.hpp"

namespace pcsim::assembly {

class CatenarySystem {
 public:
  // node_owner: reuse a partition computed before (see DofLayout).
  CatenarySystem(MPI_Comm comm, catenary::CatenaryMesh mesh, PetscInt extra_dofs = 0,
                 const std::vector<int>* node_owner = nullptr);
  ~CatenarySystem();
  CatenarySystem(const CatenarySystem&) = delete;
  CatenarySystem& operator=(const CatenarySystem&) = delete;

  const catenary::CatenaryMesh& mesh() const { return mesh_; }
  catenary::CatenaryMesh& mutable_mesh() { return mesh_; }
  const DofLayout& layout() const { return *layout_; }
  MPI_Comm comm() const { return layout_->comm(); }

  Vec create_vector() const { return layout_->create_global_vector(); }
  // Writes the design configuration (node positions and slopes) into x.
  void design_state(Vec x) const;

  // Gathers the node values (owned + ghost) of state x; later calls read them.
  void load_state(Vec x);
  // 6 values (r, r') of a needed node from the last loaded state.
  Eigen::Matrix<double, 6, 1> node_values(int node) const;

  // A constant force applied at local coordinate chi of a cable element
  // (distributed to its DOFs by the shape functions; part of kLoads).
  struct PointLoad {
    int element = -1;
    double chi = 0;
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
  };
  std::vector<PointLoad>& point_loads() { return point_loads_; }

  // Which terms assemble_static() evaluates.
  enum Terms : unsigned {
    kCables = 1u,  // ANCF cable elastic forces
    kBars = 2u,    // bars (droppers, steady arms, stitch wires)
    kLoads = 4u,   // gravity of everything, constant node forces, support springs
    kAllTerms = 7u,
    // With kBars: every bar taut, its slack criterion ignored (dropper
    // slackening off, form-finding).
    kTautBars = 8u,
  };
  // R = f_elastic - f_gravity + springs at the loaded state (R is overwritten:
  // zero outside the assembled terms). If J is not null the tangent is added
  // to J (entries only; the caller assembles J).
  void assemble_static(Vec R, Mat J, unsigned terms = kAllTerms);
  // Adds the same forces to R and their tangent to J; either may be null.
  void add_forces(Vec R, Mat J, unsigned terms = kAllTerms);
  // Potential energy of the selected terms at the loaded state, summed over
  // the elements this rank assembles (strain energy of cables and bars,
  // minus the work of gravity and point loads, spring energy).
  double local_potential_energy(unsigned terms = kAllTerms) const;
  // Inserts explicit zeros at every element coupling, so that matrices
  // duplicated from A share one nonzero pattern (fast MatAXPY, and a pattern
  // that never changes during a run). The caller assembles A.
  void insert_element_pattern(Mat A) const;
  // Consistent mass (cables) + lumped masses (bars, point masses); assembled.
  void assemble_mass(Mat M);
  // Mean axial force of a local or remote cable element at the loaded state
  // (needs the element's nodes to be needed on this rank).
  double cable_mean_tension(int element) const;
  // Axial force of a bar at the loaded state (slack = false: taut, see kTautBars).
  double bar_force(int bar, bool slack = true) const;

  // Gathers the global state to rank 0 as node positions (3 per node; the
  // design value for constrained DOFs). Empty on other ranks.
  std::vector<double> gather_positions_to_root(Vec x) const;
  // All node values (6 per node) on every rank.
  std::vector<double> all_node_values(Vec x) const;

  // Global indices of the 12 DOFs of a cable element / 6 of a bar (-1 fixed).
  void cable_indices(int element, PetscInt idx[12]) const;
  void bar_indices(int bar, PetscInt idx[6]) const;
  // Element DOF values at the loaded state.
  void cable_values(int element, double q[12]) const;
  void bar_values(int bar, double q[6]) const;

  // Gathered-layout work vector for residual contributions (zeroed by
  // begin_residual, added into R by end_residual).
  double* begin_residual();
  void end_residual(Vec R);
  void add_node_residual(double* r_local, int node, int c, double value) const;

 private:
  catenary::CatenaryMesh mesh_;
  std::unique_ptr<DofLayout> layout_;
  std::vector<double> gather_node_values(Vec x, bool to_root) const;
  void add_block(double* r, const int* nodes, int dofs_per_node, const double* f) const;
  void add_cable_forces(double* r, Mat J, bool cables, bool loads) const;
  void add_bar_forces(double* r, Mat J, bool bars, bool loads, bool slack) const;
  void add_point_forces(double* r, Mat J) const;
  void add_spring(double* r, Mat J, const catenary::SupportSpring& spring) const;
  std::vector<PointLoad> point_loads_;
  std::vector<double> node_state_;  // needed nodes x 6
  std::vector<double> design_values_;
  Vec gathered_ = nullptr, residual_gathered_ = nullptr;
  double* residual_array_ = nullptr;
};

}  // namespace pcsim::assembly
