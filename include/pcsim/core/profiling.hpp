// -log_view stages and events of pcsim (docs/scaling.md "Where the time goes").
// The stages split a run into its phases; the events time the parts of a
// step that PETSc's own events (KSPSolve, MatSolve, MatMult, VecScatter*)
// do not name.
#pragma once

#include <petscsys.h>
#include <petsctime.h>

namespace pcsim {

struct LogEvents {
  PetscLogEvent residual;         // CoupledSystem::residual: the whole residual
  PetscLogEvent linear_parts;     // the constant-matrix products K0 (dU + b V), M (A + a V)
  PetscLogEvent residual_update;  // CoupledSystem::residual_update: after an exact update
  PetscLogEvent state_load;       // ghost scatter of the catenary state + pantographs' broadcast
  PetscLogEvent contact;          // contact evaluation (wire locator + penalty kernel)
  PetscLogEvent low_rank_change;  // the terms' rank-one changes (droppers, contact)
  PetscLogEvent woodbury;         // the Woodbury correction after the J0 solve
  PetscLogEvent record;           // a step's record (contact force, supports, droppers)
  PetscLogEvent dd_setup;         // the domain-decomposition factorisation and Schur complement
  PetscLogEvent dd_apply;         // one domain-decomposition solve
  PetscLogEvent dd_interface;     // its interface solve x_G = S^-1 g (replicated)
  PetscLogEvent shift_products;   // a modal window's shift products G = V^T M S V (set-up)
  PetscLogEvent shift_gemm;       // their dense products (BLAS dgemm)
  PetscLogEvent basis_assembly;   // a reduced basis assembled from its modal data (set-up)
};

// Wall-clock time [s] by PETSc's timer (the clock of -log_view): for differences.
inline double wall_clock_s() {
  PetscLogDouble t;
  PetscTime(&t);
  return t;
}

// Registered on the first call (collective on PETSC_COMM_WORLD the first time).
const LogEvents& log_events();

// Times its lifetime as event e (exception-safe).
class ScopedEvent {
 public:
  explicit ScopedEvent(PetscLogEvent e) : event_(e) { PetscLogEventBegin(event_, 0, 0, 0, 0); }
  ~ScopedEvent() { PetscLogEventEnd(event_, 0, 0, 0, 0); }
  ScopedEvent(const ScopedEvent&) = delete;
  ScopedEvent& operator=(const ScopedEvent&) = delete;

 private:
  PetscLogEvent event_;
};

// Pushes a -log_view stage for its lifetime ("Form-finding", "Time loop", ...);
// next() pops it and pushes another.
class LogStage {
 public:
  explicit LogStage(const char* name) { next(name); }
  ~LogStage();
  void next(const char* name);
  LogStage(const LogStage&) = delete;
  LogStage& operator=(const LogStage&) = delete;

 private:
  bool pushed_ = false;
};

}  // namespace pcsim
