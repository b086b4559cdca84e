// The time integration of a coupled system: a PETSc TS (default the
// project's HHT-alpha, `-ts_type hht`) on the I2 residual/Jacobian callbacks
// of assembly::CoupledSystem, Newton (SNES) with an exact direct solve.
//
// Two Jacobian paths:
//  - full: the exact tangent assembled and factored at every Newton iteration;
//  - cheap (possible when no term is 'varying'): J0 = every term's reference
//    tangent, factored once per time-step size; the terms' low-rank changes
//    enter exactly through LowRankStepSolver (Woodbury), and a nonlinear
//    pantograph's block (decoupled from the rest in J0) is re-evaluated and
//    refactored at every iteration. The SNES's operator is J0 + changes, so
//    -snes_test_jacobian and -ksp_type work on both.
// Options (listed by -help): -pcsim_path <auto|full|cheap>. Direct solver:
// PETSc's LU with quotient-minimum-degree ordering on one rank (its solves
// measured 4x faster than MUMPS on the EN 50318 mesh), MUMPS with METIS
// ordering in parallel (2.4x faster solves than its default there); the
// cheap path's inner solver takes the prefix -cheap_.
#pragma once

#include <petscts.h>

#include <memory>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/solvers/low_rank.hpp"

namespace pcsim::solvers {

// Everything the integration needs to continue exactly as an uninterrupted
// run would (checkpoint/restart; -ts_type hht). Vectors in the global order,
// on rank 0 only (empty elsewhere); the rest is the same on every rank.
struct DynamicState {
  double t = 0;          // time of the last accepted step [s]
  long step = 0;         // its number
  double time_step = 0;  // Δt of the next step
  double user_time_step = 0;
  long accepted_since_cut = 0;  // HHT step-size control
  std::vector<double> U, V, A;  // state at t (positions, velocities, accelerations)
  // Cheap path: J0 was assembled at (reference_t, reference_U/V/A) with these
  // shifts (so that it is rebuilt bitwise equal); false before the first J0.
  bool has_reference = false;
  double reference_t = 0, shift_v = 0, shift_a = 0;
  std::vector<double> reference_U, reference_V, reference_A;
  std::vector<std::vector<double>> terms;  // Term::checkpoint() of every term
  std::vector<double> head_offsets;        // every pantograph's, set by the initial state
  // The HHT alpha-term the next step takes from the last residual (hht.hpp;
  // false: the next step evaluates it), so that a restarted run does the
  // uninterrupted one's arithmetic.
  bool has_alpha_term = false;
  std::vector<double> alpha_term;
};

class DynamicSolver {
 public:
  // dt: default time step (-ts_dt overrides); duration: final time.
  // hht_alpha: the scene's HHT alpha; -ts_hht_alpha overrides it.
  DynamicSolver(assembly::CoupledSystem& system, double dt, double duration,
                double hht_alpha = 0.1);
  ~DynamicSolver();
  DynamicSolver(const DynamicSolver&) = delete;
  DynamicSolver& operator=(const DynamicSolver&) = delete;

  TS ts() const { return ts_; }
  // No monitor lines from the options database (-ts_monitor, -snes_monitor,
  // -ksp_monitor and their variants): for runs that print nothing (an
  // accuracy pilot's, a study's), whose console is the run's. PETSc reads
  // -snes_converged_reason and -ksp_converged_reason again at every solve:
  // those still print.
  void silence_monitors();
  // Starts the TS at (U0, V0) (copied): with HHT also at the acceleration of
  // that state (assembly::initial_acceleration; zero for equilibrium starts).
  void set_initial_state(Vec U0, Vec V0);
  bool cheap_path() const { return low_rank_ != nullptr; }
  // The cheap path's step solver (null on the full path).
  const LowRankStepSolver* low_rank() const { return low_rank_.get(); }
  // Times the cheap path's J0 was assembled and factored (a new time step, or a
  // term that asked for it); 0 on the full path, which factors every iteration.
  long reference_builds() const { return reference_builds_; }
  // The KSP that factors the step matrix (J0's on the cheap path).
  KSP step_ksp() const;

  // Checkpoint/restart (collective; the TS must be of type hht). save_state()
  // after an accepted step; restore_state() instead of setting an initial
  // state, before TSSolve (which then continues from state.step).
  DynamicState save_state() const;
  void restore_state(const DynamicState& state);
  // A moving window's shift (collective; TS type hht; between steps): the
  // integration goes on from (U, V, A), given on rank 0 in the global order
  // (ignored elsewhere); on the cheap path J0 is rebuilt at the next step.
  void replace_state(const std::vector<double>& U, const std::vector<double>& V,
                     const std::vector<double>& A);
  // The residual changed between steps other than through the state (a held
  // load set from outside): the next step evaluates its HHT alpha-term.
  void residual_changed();

 private:
  static PetscErrorCode residual(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx);
  static PetscErrorCode inertia_product(TS, PetscReal t, Vec U, Vec V, Vec A, Vec MA, void* ctx);
  // The residual after an exact Newton update on the cheap path
  // (CoupledSystem::residual_update, hht_set_residual_update).
  static PetscErrorCode residual_update(TS, PetscReal t, Vec X, Vec V, Vec A, Vec Y, Vec F,
                                        PetscBool* done, void* ctx);
  bool step_solve_exact() const;
  static PetscErrorCode jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shift_v,
                                 PetscReal shift_a, Mat J, Mat P, void* ctx);
  void cheap_jacobian(PetscReal t, Vec U, Vec V, Vec A, assembly::Shifts shifts, Mat P);
  void configure_direct_solvers();

  assembly::CoupledSystem& system_;
  TS ts_ = nullptr;
  Mat P_ = nullptr;  // the assembled Jacobian (full) or J0 (cheap)
  long reference_builds_ = 0;
  std::unique_ptr<LowRankStepSolver> low_rank_;
  std::vector<assembly::RankOne> terms_;
  std::vector<assembly::BlockChange> blocks_;
  double cached_shift_v_ = -1, cached_shift_a_ = -1;
  // The state J0 was assembled at (cheap path), for checkpoints.
  double reference_t_ = 0;
  Vec reference_U_ = nullptr, reference_V_ = nullptr, reference_A_ = nullptr;
};

// -pcsim_path from the options database: true for the cheap path.
bool choose_cheap_path(MPI_Comm comm, bool possible);

}  // namespace pcsim::solvers
