// Eigenpairs and rows for the reduced basis (see modal_basis_internal.hpp).
#include <slepceps.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "modal_basis_internal.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::simulation::modal_detail {

Operators::Operators(assembly::CatenarySystem& system, Vec x) {
  const auto& L = system.layout();
  if (L.extra_dofs() != 0) throw SolverError("reduced basis: the system has extra unknowns");
  K = L.create_matrix();
  M = L.create_matrix();
  solvers::assemble_stiffness_and_mass(system, x, K, M);
}

Operators::Operators(Mat K_, Mat M_) : K(K_), M(M_) {
  PCSIM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(K)));
  PCSIM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(M)));
}

Operators::~Operators() {
  MatDestroy(&K);
  MatDestroy(&M);
}

RowGather::RowGather(const assembly::CatenarySystem& system, const std::vector<long>& keys,
                     Mat loads)
    : size_(keys.size()) {
  const auto& L = system.layout();
  std::vector<PetscInt> from;
  load_slot_ = keys.size();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (catenary::is_turbulence_row_key(system.mesh(), keys[i])) {  // the last ones
      load_slot_ = std::min(load_slot_, i);
      continue;
    }
    const PetscInt g = L.global_dof(static_cast<int>(keys[i] / 6), static_cast<int>(keys[i] % 6));
    if (g < 0) continue;
    from.push_back(g);
    slot_.push_back(i);
  }
  IS is;
  PCSIM_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(from.size()), from.data(),
                              PETSC_COPY_VALUES, &is));
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(from.size()), &local_));
  Vec global = system.create_vector();
  PCSIM_PETSC(VecScatterCreate(global, is, local_, nullptr, &scatter_));
  PCSIM_PETSC(VecDestroy(&global));
  PCSIM_PETSC(ISDestroy(&is));
  if (load_slot_ < keys.size()) {
    if (!loads) throw SolverError("reduced basis: turbulence rows without their loads");
    loads_ = loads;
    PCSIM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(loads_)));
    PCSIM_PETSC(MatCreateVecs(loads_, &forces_, nullptr));
    PCSIM_PETSC(VecScatterCreateToAll(forces_, &to_all_, &forces_all_));
  }
}

RowGather::~RowGather() {
  VecScatterDestroy(&scatter_);
  VecDestroy(&local_);
  VecScatterDestroy(&to_all_);
  VecDestroy(&forces_);
  VecDestroy(&forces_all_);
  MatDestroy(&loads_);
}

void RowGather::gather(Vec v, double* out) const {
  PCSIM_PETSC(VecScatterBegin(scatter_, v, local_, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(scatter_, v, local_, INSERT_VALUES, SCATTER_FORWARD));
  std::fill(out, out + size_, 0.0);
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(local_, &a));
  for (std::size_t k = 0; k < slot_.size(); ++k) out[slot_[k]] = a[k];
  PCSIM_PETSC(VecRestoreArrayRead(local_, &a));
  if (!loads_) return;
  PCSIM_PETSC(MatMultTranspose(loads_, v, forces_));  // phi^T L_j
  PCSIM_PETSC(VecScatterBegin(to_all_, forces_, forces_all_, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(to_all_, forces_, forces_all_, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecGetArrayRead(forces_all_, &a));
  std::copy(a, a + (size_ - load_slot_), out + load_slot_);
  PCSIM_PETSC(VecRestoreArrayRead(forces_all_, &a));
}

namespace {

// M-normalises phi (largest component positive); returns its relative residual.
double normalise(const Operators& op, double lambda, Vec phi, Vec Mphi, Vec Kphi) {
  PCSIM_PETSC(MatMult(op.M, phi, Mphi));
  PetscScalar mnorm;
  PCSIM_PETSC(VecDot(phi, Mphi, &mnorm));
  PetscReal vmax, vmin;
  PCSIM_PETSC(VecMax(phi, nullptr, &vmax));
  PCSIM_PETSC(VecMin(phi, nullptr, &vmin));
  double scale = 1.0 / std::sqrt(PetscRealPart(mnorm));
  if (std::abs(vmin) > std::abs(vmax)) scale = -scale;
  PCSIM_PETSC(VecScale(phi, scale));
  PCSIM_PETSC(VecScale(Mphi, scale));
  PCSIM_PETSC(MatMult(op.K, phi, Kphi));
  PCSIM_PETSC(VecAXPY(Kphi, -lambda, Mphi));
  PetscReal rn, mn;
  PCSIM_PETSC(VecNorm(Kphi, NORM_2, &rn));
  PCSIM_PETSC(VecNorm(Mphi, NORM_2, &mn));
  return rn / (std::abs(lambda) * mn);
}

// Number of eigenvalues below lambda: the inertia of K - lambda M (MUMPS LDL^T).
PetscInt count_below(Mat K, Mat M, double lambda) {
  Mat A;
  PCSIM_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &A));
  PCSIM_PETSC(MatAXPY(A, -lambda, M, SUBSET_NONZERO_PATTERN));
  PCSIM_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  Mat F;
  PCSIM_PETSC(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
  PCSIM_PETSC(MatMumpsSetIcntl(F, 13, 1));  // inertia of a parallel factorisation
  MatFactorInfo info;
  PCSIM_PETSC(MatFactorInfoInitialize(&info));
  PCSIM_PETSC(MatCholeskyFactorSymbolic(F, A, nullptr, &info));
  PCSIM_PETSC(MatCholeskyFactorNumeric(F, A, &info));
  PetscInt negative = 0;
  PCSIM_PETSC(MatGetInertia(F, &negative, nullptr, nullptr));
  PCSIM_PETSC(MatDestroy(&F));
  PCSIM_PETSC(MatDestroy(&A));
  return negative;
}

// The eigenpairs with lambda in [lo, hi], ascending, into the sink.
double stream_interval(const Operators& op, double lo, double hi, const ModeSink& sink) {
  EPS eps;
  PCSIM_PETSC(EPSCreate(PetscObjectComm(reinterpret_cast<PetscObject>(op.K)), &eps));
  PCSIM_PETSC(EPSSetOptionsPrefix(eps, "modal_"));
  PCSIM_PETSC(EPSSetOperators(eps, op.K, op.M));
  solvers::configure_slicing(eps, lo, hi);
  PCSIM_PETSC(EPSSetFromOptions(eps));
  PCSIM_PETSC(EPSSolve(eps));
  const auto spectrum = solvers::converged_spectrum(eps);
  const auto& lambdas = spectrum.lambdas;
  const auto& order = spectrum.order;
  Vec phi, Mphi, Kphi;
  PCSIM_PETSC(MatCreateVecs(op.K, &phi, &Mphi));
  PCSIM_PETSC(VecDuplicate(phi, &Kphi));
  double max_residual = 0;
  for (PetscInt i : order) {
    if (lambdas[i] < lo || lambdas[i] > hi) continue;  // slicing keeps [lo, hi]
    PCSIM_PETSC(EPSGetEigenvector(eps, i, phi, nullptr));
    max_residual = std::max(max_residual, normalise(op, lambdas[i], phi, Mphi, Kphi));
    sink(lambdas[i], phi);
  }
  for (Vec* v : {&phi, &Mphi, &Kphi}) PCSIM_PETSC(VecDestroy(v));
  PCSIM_PETSC(EPSDestroy(&eps));
  return max_residual;
}

// K and M on the DOFs of a group of K's connected components.
struct GroupOperators {
  IS dofs = nullptr;
  Mat K = nullptr, M = nullptr;
  Vec phi = nullptr;  // an eigenvector on the group's DOFs
  GroupOperators(const Operators& op, const std::vector<PetscInt>& owned) {
    PCSIM_PETSC(ISCreateGeneral(PetscObjectComm(reinterpret_cast<PetscObject>(op.K)),
                                static_cast<PetscInt>(owned.size()), owned.data(),
                                PETSC_COPY_VALUES, &dofs));
    PCSIM_PETSC(MatCreateSubMatrix(op.K, dofs, dofs, MAT_INITIAL_MATRIX, &K));
    PCSIM_PETSC(MatCreateSubMatrix(op.M, dofs, dofs, MAT_INITIAL_MATRIX, &M));
    for (Mat A : {K, M}) PCSIM_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
    PCSIM_PETSC(MatCreateVecs(K, &phi, nullptr));
  }
  ~GroupOperators() {
    VecDestroy(&phi);
    MatDestroy(&M);
    MatDestroy(&K);
    ISDestroy(&dofs);
  }
  GroupOperators(const GroupOperators&) = delete;
  GroupOperators& operator=(const GroupOperators&) = delete;
  // Eigenvalues in (lambda_above, lambda]; lambda_above 0: in [0, lambda].
  PetscInt count(double lambda_above, double lambda) const {
    return count_below(K, M, lambda) - (lambda_above > 0 ? count_below(K, M, lambda_above) : 0);
  }
};

EPS solve_interval(Mat K, Mat M, double lo, double hi) {
  EPS eps;
  PCSIM_PETSC(EPSCreate(PetscObjectComm(reinterpret_cast<PetscObject>(K)), &eps));
  PCSIM_PETSC(EPSSetOptionsPrefix(eps, "modal_"));
  PCSIM_PETSC(EPSSetOperators(eps, K, M));
  solvers::configure_slicing(eps, lo, hi);
  PCSIM_PETSC(EPSSetFromOptions(eps));
  PCSIM_PETSC(EPSSolve(eps));
  return eps;
}

// An eigenpair of one group in an interval's solve.
struct GroupPair {
  double lambda;
  std::size_t group;
  PetscInt index;  // in the group's EPS
};

// The groups' eigenpairs in [lo, hi], each group solved on its own DOFs,
// into the sink in ascending order (each mode zero outside its group).
double stream_groups_interval(const Operators& op,
                              const std::vector<std::unique_ptr<GroupOperators>>& groups,
                              const std::vector<bool>& any, double lo, double hi,
                              const ModeSink& sink) {
  std::vector<EPS> eps(groups.size(), nullptr);
  std::vector<GroupPair> pairs;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (!any[g]) continue;  // (the slicing of an interval without eigenvalues is not asked)
    eps[g] = solve_interval(groups[g]->K, groups[g]->M, lo, hi);
    const auto spectrum = solvers::converged_spectrum(eps[g]);
    for (PetscInt i : spectrum.order)
      if (spectrum.lambdas[i] >= lo && spectrum.lambdas[i] <= hi)
        pairs.push_back({spectrum.lambdas[i], g, i});
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const GroupPair& a, const GroupPair& b) { return a.lambda < b.lambda; });
  Vec phi, Mphi, Kphi;
  PCSIM_PETSC(MatCreateVecs(op.K, &phi, &Mphi));
  PCSIM_PETSC(VecDuplicate(phi, &Kphi));
  double max_residual = 0;
  for (const GroupPair& p : pairs) {
    const GroupOperators& group = *groups[p.group];
    PCSIM_PETSC(EPSGetEigenvector(eps[p.group], p.index, group.phi, nullptr));
    PCSIM_PETSC(VecSet(phi, 0.0));
    PCSIM_PETSC(VecISCopy(phi, group.dofs, SCATTER_FORWARD, group.phi));
    max_residual = std::max(max_residual, normalise(op, p.lambda, phi, Mphi, Kphi));
    sink(p.lambda, phi);
  }
  for (Vec* v : {&phi, &Mphi, &Kphi}) PCSIM_PETSC(VecDestroy(v));
  for (EPS& e : eps) EPSDestroy(&e);
  return max_residual;
}

// Streams one interval's modes [lo, hi] into a sink; returns their largest residual.
using Interval = std::function<double(double lo, double hi, const ModeSink& sink)>;

struct Chunks {
  double lambda_above, lambda_max;
  int count;        // intervals, of equal widths in frequency
  long modes;       // in all of them (progress)
  int parts_apart;  // (progress)
};

// The intervals from lambda_above to lambda_max, each by 'interval' in turn,
// with the progress after each. [lo, hi] intervals do not overlap (nor the
// modes above lambda_above with those below).
double stream_chunks(const Chunks& chunks, const Interval& interval, const ModeSink& sink,
                     const std::function<void(long, long, int)>& progress) {
  const double omega_min = std::sqrt(std::max(chunks.lambda_above, 0.0));
  const double omega_max = std::sqrt(chunks.lambda_max);
  double max_residual = 0;
  double lo =
      chunks.lambda_above > 0 ? std::nextafter(chunks.lambda_above, 2 * chunks.lambda_above) : 0;
  long done = 0;
  const ModeSink counting = [&](double lambda, Vec phi) {
    ++done;
    sink(lambda, phi);
  };
  if (progress) progress(0, chunks.modes, chunks.parts_apart);
  for (int c = 1; c <= chunks.count; ++c) {
    const double hi = c == chunks.count
                          ? chunks.lambda_max
                          : std::pow(omega_min + (omega_max - omega_min) * c / chunks.count, 2);
    max_residual = std::max(max_residual, interval(lo, hi, counting));
    lo = std::nextafter(hi, 2 * hi);
    if (progress) progress(done, chunks.modes, chunks.parts_apart);
  }
  return max_residual;
}

// stream_modes on a K whose graph falls into separate groups of components
// (a line's tension sections share no element): each group's spectrum is
// sliced on its own DOFs, so each solve and each orthogonalisation runs over
// its group's DOFs and modes only; the same modes, in the same order, over
// intervals that hold about chunk_modes of the largest group's.
double stream_modes_by_group(const Operators& op, const std::vector<std::vector<PetscInt>>& parts,
                             double lambda_above, double lambda_max, double chunk_modes,
                             const ModeSink& sink,
                             const std::function<void(long, long, int)>& progress) {
  std::vector<std::unique_ptr<GroupOperators>> groups;
  PetscInt count = 0, largest = 0;
  for (const auto& part : parts) {
    groups.push_back(std::make_unique<GroupOperators>(op, part));
    const PetscInt n = groups.back()->count(lambda_above, lambda_max);
    count += n;
    largest = std::max(largest, n);
  }
  const int chunks = std::max(1, static_cast<int>(std::ceil(largest / chunk_modes)));
  std::vector<PetscInt> below_lo(groups.size(), 0);  // each group's count up to lo
  const Interval interval = [&](double lo, double hi, const ModeSink& counting) {
    std::vector<bool> any(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const PetscInt below_hi = groups[g]->count(lambda_above, hi);
      any[g] = below_hi > below_lo[g];
      below_lo[g] = below_hi;
    }
    return stream_groups_interval(op, groups, any, lo, hi, counting);
  };
  return stream_chunks({lambda_above, lambda_max, chunks, count, static_cast<int>(groups.size())},
                       interval, sink, progress);
}

}  // namespace

// Chunks of about chunk_modes modes (equal widths in frequency: the modal
// density of a tensioned line is about constant in f), so that SLEPc holds
// one chunk's eigenvectors at a time.
double stream_modes(const Operators& op, double lambda_above, double lambda_max,
                    const ModeSink& sink, const std::function<void(long, long, int)>& progress,
                    double chunk_modes, long min_group_dofs) {
  if (lambda_above >= lambda_max) return 0;  // (the same cut-off again: nothing above)
  PetscBool whole = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetBool(nullptr, nullptr, "-pcsim_debug_modes_whole", &whole, nullptr));
  const auto groups =
      whole ? std::vector<std::vector<PetscInt>>{} : component_groups(op.K, min_group_dofs);
  if (groups.size() > 1)
    return stream_modes_by_group(op, groups, lambda_above, lambda_max, chunk_modes, sink, progress);
  const PetscInt count = count_below(op.K, op.M, lambda_max) -
                         (lambda_above > 0 ? count_below(op.K, op.M, lambda_above) : 0);
  const int chunks = std::max(1, static_cast<int>(std::ceil(count / chunk_modes)));
  const Interval interval = [&](double lo, double hi, const ModeSink& counting) {
    return stream_interval(op, lo, hi, counting);
  };
  return stream_chunks({lambda_above, lambda_max, chunks, count, 1}, interval, sink, progress);
}

namespace {

// A copy of a distributed matrix as a dense matrix on every rank.
Eigen::MatrixXd dense_copy(Mat A) {
  PetscInt n;
  PCSIM_PETSC(MatGetSize(A, &n, nullptr));
  Mat* sub = whole_on_every_rank(A);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt ncols;
    const PetscInt* cols;
    const PetscScalar* vals;
    PCSIM_PETSC(MatGetRow(sub[0], i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; ++k) D(i, cols[k]) = vals[k];
    PCSIM_PETSC(MatRestoreRow(sub[0], i, &ncols, &cols, &vals));
  }
  PCSIM_PETSC(MatDestroySubMatrices(1, &sub));
  return 0.5 * (D + D.transpose());
}

}  // namespace

double stream_all_modes_dense(const Operators& op, const ModeSink& sink) {
  constexpr PetscInt kMaxDense = 4000;
  PetscInt n;
  PCSIM_PETSC(MatGetSize(op.K, &n, nullptr));
  if (n > kMaxDense)
    throw SolverError("reduced basis: every mode (no cut-off) is for structures up to " +
                      std::to_string(kMaxDense) + " unknowns; this one has " + std::to_string(n));
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(dense_copy(op.K),
                                                                         dense_copy(op.M));
  if (solver.info() != Eigen::Success) throw SolverError("reduced basis: dense eigensolve failed");
  Vec phi, Mphi, Kphi;
  PCSIM_PETSC(MatCreateVecs(op.K, &phi, &Mphi));
  PCSIM_PETSC(VecDuplicate(phi, &Kphi));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(phi, &lo, &hi));
  double max_residual = 0;
  for (PetscInt k = 0; k < n; ++k) {
    PetscScalar* a;
    PCSIM_PETSC(VecGetArray(phi, &a));
    for (PetscInt i = lo; i < hi; ++i) a[i - lo] = solver.eigenvectors()(i, k);
    PCSIM_PETSC(VecRestoreArray(phi, &a));
    const double lambda = solver.eigenvalues()[k];
    max_residual = std::max(max_residual, normalise(op, lambda, phi, Mphi, Kphi));
    sink(lambda, phi);
  }
  for (Vec* v : {&phi, &Mphi, &Kphi}) PCSIM_PETSC(VecDestroy(v));
  return max_residual;
}

}  // namespace pcsim::simulation::modal_detail
