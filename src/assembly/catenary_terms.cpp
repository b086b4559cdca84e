#include "pcsim/assembly/catenary_terms.hpp"

#include <mpi.h>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {
constexpr unsigned kCablesAndLoads = CatenarySystem::kCables | CatenarySystem::kLoads;

double sum_over_ranks(MPI_Comm comm, double local) {
  double total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  return total;
}
}  // namespace

// ------------------------------------------------- nonlinear cables ----

void NonlinearCableForces::add_residual(const CoupledState&, Vec F) {
  catenary_.system().add_forces(F, nullptr, kCablesAndLoads);
}

void NonlinearCableForces::add_tangent(const CoupledState&, Shifts, Mat J) {
  catenary_.system().add_forces(nullptr, J, kCablesAndLoads);
}

double NonlinearCableForces::energy(const CoupledState&) const {
  return sum_over_ranks(catenary_.comm(),
                        catenary_.system().local_potential_energy(kCablesAndLoads));
}

// ------------------------------------------------ linearised cables ----

LinearisedCableForces::LinearisedCableForces(FECatenary& catenary)
    : catenary_(catenary),
      K0_(catenary.static_tangent(kCablesAndLoads)),
      b0_(catenary.static_forces(kCablesAndLoads)) {}

LinearisedCableForces::~LinearisedCableForces() {
  VecDestroy(&work_);
  VecDestroy(&work2_);
}

void LinearisedCableForces::add_residual(const CoupledState&, Vec F) {
  PCSIM_PETSC(VecAXPY(F, 1.0, b0_));
}

double LinearisedCableForces::energy(const CoupledState& state) const {
  auto* self = const_cast<LinearisedCableForces*>(this);
  if (!work_) {
    self->work_ = catenary_.create_vector();
    self->work2_ = catenary_.create_vector();
  }
  PCSIM_PETSC(VecWAXPY(work_, -1.0, catenary_.reference_vector(), state.U));
  PCSIM_PETSC(MatMult(K0_, work_, work2_));
  PetscScalar uku = 0, bu = 0;
  PCSIM_PETSC(VecDot(work_, work2_, &uku));
  PCSIM_PETSC(VecDot(b0_, work_, &bu));
  return bu + 0.5 * uku;
}

// --------------------------------------------------------- inertia ----

double Inertia::energy(const CoupledState& state) const {
  if (!state.V) return 0;
  Vec MV = catenary_.create_vector();
  PCSIM_PETSC(MatMult(M_, state.V, MV));
  PetscScalar vmv = 0;
  PCSIM_PETSC(VecDot(state.V, MV, &vmv));
  PCSIM_PETSC(VecDestroy(&MV));
  return 0.5 * vmv;
}

// ------------------------------------------------------- Rayleigh ----

RayleighDamping::RayleighDamping(FECatenary& catenary, const contact::InteractionEffects& e) {
  const double alpha = catenary.mesh().rayleigh_alpha, beta = catenary.mesh().rayleigh_beta;
  const unsigned taut = e.dropper_slack ? 0u : CatenarySystem::kTautBars;
  // Every constant matrix holds a subset of the Jacobian's pattern (FECatenary).
  parts_.push_back({catenary.mass_matrix(), 0.0, alpha, 0.0, SUBSET_NONZERO_PATTERN});
  if (catenary.fidelity() == catenary::CatenaryFidelity::nonlinear) {
    parts_.push_back({catenary.static_tangent(CatenarySystem::kAllTerms | taut), 0.0, beta, 0.0,
                      SUBSET_NONZERO_PATTERN});
  } else {
    // K0 (cables, loads) is the linearised cables' matrix: the products merge.
    parts_.push_back(
        {catenary.static_tangent(kCablesAndLoads), 0.0, beta, 0.0, SUBSET_NONZERO_PATTERN});
    parts_.push_back(
        {catenary.static_tangent(CatenarySystem::kBars | taut | FECatenary::kOwnPattern), 0.0, beta,
         0.0, SUBSET_NONZERO_PATTERN});
  }
}

TermPower RayleighDamping::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  for (const auto& part : parts_) p.dissipative -= part.cv * quadratic_form(part.matrix, state.V);
  return p;
}

double quadratic_form(Mat C, Vec v) {
  Vec Cv;
  PCSIM_PETSC(VecDuplicate(v, &Cv));
  PCSIM_PETSC(MatMult(C, v, Cv));
  PetscScalar vcv = 0;
  PCSIM_PETSC(VecDot(v, Cv, &vcv));
  PCSIM_PETSC(VecDestroy(&Cv));
  return vcv;
}

}  // namespace pcsim::assembly
