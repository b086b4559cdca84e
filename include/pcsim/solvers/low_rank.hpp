// A step matrix J = J0 + sum_k c_k u_k u_k^T with J0 factored once: the
// operator (a MATSHELL, so that the SNES holds the true Jacobian and
// -snes_test_jacobian or any -ksp_type work) and its exact inverse by the
// Woodbury formula in a PC of its own type (pcsimwoodbury):
//   J^-1 r = y - Z (C^-1 + U^T Z)^-1 U^T y,  y = J0^-1 r,  Z = J0^-1 U.
// The rank-one terms come from the coupled system's terms (contact, switched
// droppers); this class never knows what they are. A term whose u keeps
// recurring on the same unknowns (reuse_columns: a contact moving along the
// wire) gets z = J0^-1 u combined from cached unit solves J0^-1 e_g, so a new
// solve is needed only when it reaches new unknowns (also right after a
// refactorisation: z is a function of J0 and u alone, whatever the history,
// so a restarted run computes the same z as an uninterrupted one). J0 is factored by an
// inner KSP with options prefix -cheap_ (e.g. -cheap_pc_factor_mat_solver_type), or,
// when its pattern is block diagonal with small blocks (the reduced-order catenary's)
// and no -cheap_pc_type is given, inverted block by block (block_diagonal.hpp).
// 'Block' terms (a nonlinear pantograph, assembly/term.hpp) change a small
// dense diagonal block of J0 that J0 couples with nothing else: the operator
// adds the change, and J0^-1 takes those rows from the block's LU (dense, or
// sparse for a large block with few entries), refactored at every Jacobian
// (varying_blocks.hpp); J0 stays factored.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "pcsim/assembly/term.hpp"

namespace pcsim::solvers {

// The PC type of the cheap path's step solver (-pc_type pcsimwoodbury).
inline constexpr const char* kPCWoodbury = "pcsimwoodbury";

class BlockDiagonalInverse;
class VaryingBlocks;

struct CapacitanceDots;  // src/solvers/capacitance_dots.hpp

class LowRankStepSolver {
 public:
  // J0: the factored part (the SNES's preconditioning matrix).
  LowRankStepSolver(Mat J0, const char* inner_prefix);
  ~LowRankStepSolver();
  LowRankStepSolver(const LowRankStepSolver&) = delete;
  LowRankStepSolver& operator=(const LowRankStepSolver&) = delete;

  Mat op() const { return op_; }  // J0 + sum c u u^T
  // Makes pc the Woodbury preconditioner (exact inverse of op()): the PC
  // type pcsimwoodbury (-pc_type) with this solver attached.
  void install(PC pc);
  static void register_pc();  // PCRegister once (idempotent)
  // J0 changed (reassembled): the factorisation and every J0^-1 u are stale
  // until the PC is set up again.
  void invalidate();
  // The current rank-one terms (identical on every rank) and block changes,
  // at every Jacobian evaluation. Terms keep their J0^-1 u while their u
  // stays the same (but for the rows of varying blocks).
  void set_terms(const std::vector<assembly::RankOne>& terms,
                 const std::vector<assembly::BlockChange>& blocks = {});
  KSP inner() const { return inner_; }
  // y += (op() - J0) x: the rank-one terms and the block changes alone,
  // without a product with J0. The products u_k . x come from the last
  // application of the inverse when x is its result (no communication: u_k . x
  // = w_k - (U^T Z s)_k from its own w and s), else from the terms' entries
  // (one reduction).
  void add_change_product(Vec x, Vec y) const;
  // True when the inverse is exact to round-off: J0 inverted by blocks, or the
  // inner KSP is preonly with a factorisation (LU, Cholesky, pcsim's exact
  // domain decomposition).
  bool solves_exactly() const;
  // J0 is inverted block by block (known after the first setup), not by the inner KSP.
  bool block_inverse() const { return blocks_ != nullptr; }
  // This rank's sparse varying blocks' factorisations, and those refactored
  // in the pivot order of J0's block (src/solvers/klu_lu.hpp).
  long sparse_block_factorisations() const;
  long kept_order_factorisations() const;
  // Counts since construction, for the step-time report: the times the set
  // of active rank-one terms changed (a contact opened or closed, a dropper
  // went slack or taut) and the capacitance's rows formed (a moving
  // contact's each step; every row of a changed set but those kept).
  long active_set_changes() const { return active_set_changes_; }
  long capacitance_rows_formed() const { return capacitance_rows_formed_; }
  std::size_t active_terms() const { return active_.size(); }
  // The capacitance forms each pair of terms' product once (J0 inverted by
  // blocks and symmetric bit for bit at its last setup, no varying block).
  bool symmetric_capacitance() const;

 private:
  struct Entry {
    assembly::RankOne term;
    Vec u = nullptr, z = nullptr;
    bool z_valid = false;
    bool changed = true;  // u or z since the capacitance's products
    bool sparse = false;  // u's entries few and none twice: its products read only them
  };
  static PetscErrorCode pc_create(PC pc);
  static LowRankStepSolver* attached(PC pc);  // the solver install() attached
  static PetscErrorCode pc_setup(PC pc);
  static PetscErrorCode pc_apply(PC pc, Vec r, Vec x);
  static PetscErrorCode op_mult(Mat A, Vec x, Vec y);
  void take_vectors(Entry& e);
  void reserve_vectors(std::size_t count);
  void build_u(Entry& e);
  void update_z(Entry& e);
  Vec unit_solution(PetscInt g);
  void evict_unused_columns();
  void update_capacitance(Vec x, std::vector<PetscScalar>& ux);
  CapacitanceDots active_dots() const;  // the active terms' u and z (capacitance_dots.hpp)
  void choose_inner(Mat P);
  void solve_j0(Vec r, Vec x) const;     // with the varying blocks' current values
  void solve_fixed(Vec r, Vec x) const;  // J0 as factored
  std::vector<Entry*> active();

  Mat J0_, op_ = nullptr;
  KSP inner_ = nullptr;
  std::unique_ptr<BlockDiagonalInverse> blocks_;        // J0 block diagonal: inverted by blocks
  std::unique_ptr<VaryingBlocks> varying_;              // 'block' terms' changes
  std::vector<std::pair<PetscInt, PetscInt>> skipped_;  // varying rows blocks_ leaves out
  bool factored_ = false, capacitance_dirty_ = true, inner_chosen_ = false;
  // J0, inverted by blocks, equals its transpose bit for bit (checked at
  // each setup; not a J0 factored whole, the FE catenary's, whose step is its
  // solves: the check would transpose it): then
  // u_i . J0^-1 u_j = u_j . J0^-1 u_i, and the capacitance forms each pair's
  // product once (update_capacitance), unless a varying block changes J0.
  bool j0_symmetric_ = false;
  std::map<int, Entry> entries_;
  std::vector<std::pair<Vec, Vec>> spare_;  // (u, z) of terms that left, for the next ones
  static constexpr std::size_t kReservedTerms = 16;
  std::map<PetscInt, Vec> columns_;                      // J0^-1 e_g
  Vec unit_ = nullptr;                                   // e_g during its solve
  Vec unit_solution_ = nullptr;                          // a template of J0^-1 e_g
  Eigen::MatrixXd products_;                             // U^T Z over the active terms
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_lu_;  // of C^-1 + U^T Z
  std::vector<Entry*> active_;
  long active_set_changes_ = 0, capacitance_rows_formed_ = 0;
  // The last application's result x, its state, U^T y and the correction s
  // (x = y + Z s): U^T x = U^T y + (U^T Z) s without a reduction.
  struct LastApply {
    Vec x = nullptr;
    PetscObjectState state = 0;
    Eigen::VectorXd uy, s;
  } last_apply_;
  bool products_of_last_apply(Vec x, std::vector<double>& dots) const;
};

}  // namespace pcsim::solvers
