#include "pcsim/solvers/modes.hpp"

#include <petsctime.h>
#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "pcsim/core/blas_kernels.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/command_line.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::solvers {

using catenary::ModesResult;

namespace {
// Read as text: a malformed value is an input error naming the option.
PetscErrorCode read_modes_options(MPI_Comm comm, char* count, char* fmax, std::size_t size,
                                  PetscBool* count_set, PetscBool* fmax_set) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim modes", "pcsim");
  PetscCall(PetscOptionsString("-eps_nev", "number of catenary modes, >= 1 (scene modes.count)",
                               "pcsim modes", count, count, size, count_set));
  PetscCall(PetscOptionsString("-modes_fmax",
                               "every mode below this frequency [Hz], >= 0 (scene "
                               "modes.max_frequency_hz; 0: use the count)",
                               "pcsim modes", fmax, fmax, size, fmax_set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

ModesRequest modes_request_from_options(MPI_Comm comm, ModesRequest scene_values) {
  ModesRequest r = scene_values;
  char count[64], fmax[64];
  std::snprintf(count, sizeof count, "%d", r.count);
  std::snprintf(fmax, sizeof fmax, "%g", r.max_frequency_hz);
  PetscBool count_set = PETSC_FALSE, fmax_set = PETSC_FALSE;
  PCSIM_PETSC(read_modes_options(comm, count, fmax, sizeof count, &count_set, &fmax_set));
  if (count_set) {
    const long n = parse_int_option("-eps_nev", count);
    if (n < 1 || n > 1000000)
      throw InputError("command line", "-eps_nev",
                       "must be a number of modes from 1 to 1e6 (got " + std::string(count) + ")");
    r.count = static_cast<int>(n);
  }
  if (fmax_set) {
    const double f = parse_real_option("-modes_fmax", fmax);
    if (f < 0)
      throw InputError("command line", "-modes_fmax",
                       "must be >= 0 (0: use the count; got " + std::string(fmax) + ")");
    r.max_frequency_hz = f;
  }
  return r;
}

bool use_line_cholesky(PC pc) {
  PetscMPIInt ranks;
  PCSIM_PETSC(MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(pc)), &ranks));
  PCSIM_PETSC(PCSetType(pc, PCCHOLESKY));
  if (ranks > 1) {
    PCSIM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    return true;
  }
  PCSIM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERPETSC));
  PCSIM_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGRCM));
  return false;
}

void use_line_cholesky_on_every_rank(PC pc) {
  PetscMPIInt ranks;
  PCSIM_PETSC(MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(pc)), &ranks));
  if (ranks == 1) {
    use_line_cholesky(pc);
    return;
  }
  PCSIM_PETSC(PCSetType(pc, PCREDUNDANT));
  PCSIM_PETSC(PCRedundantSetNumber(pc, ranks));  // one rank per copy
  KSP inner;
  PC inner_pc;
  PCSIM_PETSC(PCRedundantGetKSP(pc, &inner));  // (options are read after)
  PCSIM_PETSC(KSPSetType(inner, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(inner, &inner_pc));
  use_line_cholesky(inner_pc);
}

int slicing_parts(MPI_Comm comm, const char* prefix) {
  PetscMPIInt ranks;
  PCSIM_PETSC(MPI_Comm_size(comm, &ranks));
  char text[64] = "";
  PetscBool set = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetString(nullptr, prefix, "-eps_krylovschur_partitions", text,
                                    sizeof text, &set));
  if (!set) return ranks;
  const std::string option =
      std::string("-") + (prefix ? prefix : "") + "eps_krylovschur_partitions";
  const long parts = parse_int_option(option, text);
  if (parts < 1 || parts > ranks)
    throw InputError("command line", option,
                     "must be a number of slices from 1 to the number of ranks, " +
                         std::to_string(ranks) + " (got " + text + ")");
  return static_cast<int>(parts);
}

// Spectrum slicing (spectrum.hpp). The basis vectors contiguous (SLEPc's
// default: the orthogonalisation in the BLAS's dgemv) with an optimised BLAS,
// as separate Vecs with the reference BLAS, whose dgemv PETSc's multi-vector
// kernels outrun ~3x (docs/benchmarks.md, "What the first modal run costs").
// On several ranks each rank slices a part of the interval on its own
// (SLEPc's multi-communicator slicing) with the one-rank factorisation:
// parts of equal width in omega, which hold about as many of a line's modes
// (uniform in omega, as a string's). With MUMPS's parallel factors the
// slicing took ~10 times as long on 2 ranks as on one (docs/benchmarks.md,
// "The modes on several ranks"). Options (-st_pc_factor_mat_solver_type,
// -bv_type, -eps_krylovschur_partitions) still win.
void configure_slicing(EPS eps, double lambda_lo, double lambda_hi) {
  ST st;
  KSP ksp;
  PC pc;
  BV bv;
  PCSIM_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  PCSIM_PETSC(EPSGetST(eps, &st));
  PCSIM_PETSC(STSetType(st, STSINVERT));
  PCSIM_PETSC(EPSSetType(eps, EPSKRYLOVSCHUR));
  PCSIM_PETSC(EPSGetBV(eps, &bv));
  PCSIM_PETSC(BVSetType(bv, blas_kernels().optimised() ? BVSVEC : BVVECS));
  PCSIM_PETSC(EPSSetInterval(eps, lambda_lo, lambda_hi));
  PCSIM_PETSC(EPSSetWhichEigenpairs(eps, EPS_ALL));
  PCSIM_PETSC(EPSSetTolerances(eps, 1e-12, 200));
  const char* prefix = nullptr;
  PCSIM_PETSC(EPSGetOptionsPrefix(eps, &prefix));
  const PetscInt parts = slicing_parts(PetscObjectComm(reinterpret_cast<PetscObject>(eps)), prefix);
  if (parts > 1) {
    PCSIM_PETSC(EPSKrylovSchurSetPartitions(eps, parts));
    const double omega_lo = std::sqrt(std::max(lambda_lo, 0.0));
    const double omega_hi = std::sqrt(lambda_hi);
    std::vector<PetscReal> ends(static_cast<std::size_t>(parts) + 1);
    for (PetscInt i = 0; i <= parts; ++i) {
      const double omega = omega_lo + (omega_hi - omega_lo) * static_cast<double>(i) / parts;
      ends[i] = omega * omega;
    }
    ends.front() = lambda_lo;  // (exactly the interval's ends)
    ends.back() = lambda_hi;
    PCSIM_PETSC(EPSKrylovSchurSetSubintervals(eps, ends.data()));
  }
  PCSIM_PETSC(EPSKrylovSchurGetKSP(eps, &ksp));  // a part's solver, on its ranks
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  if (!use_line_cholesky(pc)) return;
  // The inertia of a parallel MUMPS factorisation needs ICNTL(13) = 1 (no
  // ScaLAPACK root); -st_mat_mumps_icntl_13 still wins (read at setup).
  PCSIM_PETSC(PCFactorSetUpMatSolverType(pc));
  Mat F;
  PCSIM_PETSC(PCFactorGetMatrix(pc, &F));
  PCSIM_PETSC(MatMumpsSetIcntl(F, 13, 1));
}

namespace {

// Shift-and-invert about 0 for the nev lowest modes, or spectrum slicing
// over [0, omega_max^2].
void configure_eps(EPS eps, int nev, double max_frequency_hz) {
  if (max_frequency_hz > 0) {
    const double omega_max = 2 * M_PI * max_frequency_hz;
    configure_slicing(eps, 0.0, omega_max * omega_max);
    PCSIM_PETSC(EPSSetFromOptions(eps));
    return;
  }
  ST st;
  KSP ksp;
  PC pc;
  PCSIM_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  PCSIM_PETSC(EPSGetST(eps, &st));
  PCSIM_PETSC(STSetType(st, STSINVERT));
  PCSIM_PETSC(STGetKSP(st, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PCSIM_PETSC(EPSSetTarget(eps, 0.0));
  PCSIM_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  // On one rank PETSc's Cholesky (RCM), whose solves took 4.9 ms against
  // MUMPS's 154 ms on 100 spans (docs/catenary.md, benchmark); on several a
  // copy of it on every rank: 20 modes of 1000 spans took 12.7 s on 2 ranks
  // so, 151.6 s with MUMPS's factors over both (docs/benchmarks.md, "The
  // modes on several ranks"). No inertia needed here.
  use_line_cholesky_on_every_rank(pc);
  PCSIM_PETSC(EPSSetTolerances(eps, 1e-12, 200));
  PCSIM_PETSC(EPSSetFromOptions(eps));
}

// Mode j of the solution (ascending order): mass-normalised, sign fixed
// (largest component positive) so that shapes compare across runs; its
// relative residual into the result, its shape if asked.
void extract_mode(EPS eps, PetscInt i, double lambda, Mat K, Mat M, Vec phi, Vec Kphi, Vec Mphi,
                  const assembly::CatenarySystem& system, bool want_shape, ModesResult& result) {
  result.frequencies_hz.push_back(std::sqrt(std::max(lambda, 0.0)) / (2 * M_PI));
  PCSIM_PETSC(EPSGetEigenvector(eps, i, phi, nullptr));
  PCSIM_PETSC(MatMult(M, phi, Mphi));
  PetscScalar mnorm;
  PCSIM_PETSC(VecDot(phi, Mphi, &mnorm));
  PetscReal vmax, vmin;
  PetscInt imax, imin;
  PCSIM_PETSC(VecMax(phi, &imax, &vmax));
  PCSIM_PETSC(VecMin(phi, &imin, &vmin));
  double scale = 1.0 / std::sqrt(PetscRealPart(mnorm));
  if (std::abs(vmin) > std::abs(vmax)) scale = -scale;
  PCSIM_PETSC(VecScale(phi, scale));
  PCSIM_PETSC(VecScale(Mphi, scale));
  PCSIM_PETSC(MatMult(K, phi, Kphi));
  PCSIM_PETSC(VecAXPY(Kphi, -lambda, Mphi));
  PetscReal rn, mn;
  PCSIM_PETSC(VecNorm(Kphi, NORM_2, &rn));
  PCSIM_PETSC(VecNorm(Mphi, NORM_2, &mn));
  result.max_relative_residual =
      std::max(result.max_relative_residual, rn / (std::abs(lambda) * mn));
  if (!want_shape) return;
  // Displacement DOFs only; constrained ones are zero.
  const auto& L = system.layout();
  const auto& mesh = system.mesh();
  std::vector<double> shape(3 * mesh.nodes.size(), 0.0);
  const std::vector<double> values = system.all_node_values(phi);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c)
      shape[3 * n + c] = L.global_dof(static_cast<int>(n), c) >= 0 ? values[6 * n + c] : 0.0;
  result.shapes.push_back(std::move(shape));
}

}  // namespace

void assemble_stiffness_and_mass(assembly::CatenarySystem& system, Vec x, Mat K, Mat M) {
  system.load_state(x);
  PCSIM_PETSC(MatZeroEntries(K));
  system.add_forces(nullptr, K);
  PCSIM_PETSC(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  system.assemble_mass(M);
  PCSIM_PETSC(MatSetOption(K, MAT_SYMMETRIC, PETSC_TRUE));
  PCSIM_PETSC(MatSetOption(M, MAT_SYMMETRIC, PETSC_TRUE));
}

ModesResult compute_modes(assembly::CatenarySystem& system, Vec x, int nev, double max_frequency_hz,
                          bool want_shapes) {
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  const auto& L = system.layout();
  if (L.extra_dofs() != 0) throw SolverError("compute_modes needs a system without extra unknowns");
  Mat K = L.create_matrix(), M = L.create_matrix();
  assemble_stiffness_and_mass(system, x, K, M);
  EPS eps;
  PCSIM_PETSC(EPSCreate(L.comm(), &eps));
  PCSIM_PETSC(EPSSetOperators(eps, K, M));
  configure_eps(eps, nev, max_frequency_hz);
  PCSIM_PETSC(EPSSolve(eps));

  const bool slicing = max_frequency_hz > 0;
  ModesResult result;
  result.requested = slicing ? -1 : nev;
  const auto spectrum = converged_spectrum(eps);
  const auto& lambdas = spectrum.lambdas;
  const auto& order = spectrum.order;
  const auto nconv = static_cast<PetscInt>(lambdas.size());
  const PetscInt keep = slicing ? nconv : std::min<PetscInt>(nconv, nev);
  result.converged = static_cast<int>(nconv);
  Vec phi, Kphi, Mphi;
  PCSIM_PETSC(VecDuplicate(x, &phi));
  PCSIM_PETSC(VecDuplicate(x, &Kphi));
  PCSIM_PETSC(VecDuplicate(x, &Mphi));
  for (PetscInt j = 0; j < keep; ++j)
    extract_mode(eps, order[j], lambdas[order[j]], K, M, phi, Kphi, Mphi, system, want_shapes,
                 result);
  for (Vec* v : {&phi, &Kphi, &Mphi}) PCSIM_PETSC(VecDestroy(v));
  PCSIM_PETSC(EPSDestroy(&eps));
  PCSIM_PETSC(MatDestroy(&K));
  PCSIM_PETSC(MatDestroy(&M));
  if (!slicing && nconv < nev)
    throw SolverError("SLEPc converged only " + std::to_string(nconv) + " of " +
                      std::to_string(nev) + " modes; try -eps_ncv or -eps_max_it");
  PetscTime(&t1);
  result.wall_time_s = t1 - t0;
  return result;
}

ConvergedSpectrum converged_spectrum(EPS eps) {
  PetscInt nconv = 0;
  PCSIM_PETSC(EPSGetConverged(eps, &nconv));
  ConvergedSpectrum s;
  s.lambdas.resize(nconv);
  for (PetscInt i = 0; i < nconv; ++i) {
    PetscScalar kr, ki;
    PCSIM_PETSC(EPSGetEigenvalue(eps, i, &kr, &ki));
    s.lambdas[i] = PetscRealPart(kr);
  }
  s.order.resize(nconv);
  std::iota(s.order.begin(), s.order.end(), 0);
  std::sort(s.order.begin(), s.order.end(),
            [&](PetscInt a, PetscInt b) { return s.lambdas[a] < s.lambdas[b]; });
  return s;
}

}  // namespace pcsim::solvers
