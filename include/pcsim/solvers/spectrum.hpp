// SLEPc spectrum slicing over an interval of omega^2, shared by the catenary
// modes (solvers/modes.cpp) and the reduced basis (simulation/modal_basis*.cpp).
#pragma once

#include <slepceps.h>

#include <vector>

namespace pcsim::assembly {
class CatenarySystem;
}

namespace pcsim::solvers {

// The tangent stiffness K at state x and the mass M of a catenary system,
// into matrices created by its layout; both flagged symmetric (a conservative
// system: the flag removes round-off asymmetry).
void assemble_stiffness_and_mass(assembly::CatenarySystem& system, Vec x, Mat K, Mat M);

// A Cholesky factorisation (with its inertia) of a line's symmetric matrix
// for pc: on one rank PETSc's own LDL^T with a reverse Cuthill-McKee
// ordering (a narrow band, fill ratio ~1.6: its solves take a quarter of
// MUMPS's, docs/benchmarks.md "What the first modal run costs"); in
// parallel MUMPS. Returns true for MUMPS. Options still win.
bool use_line_cholesky(PC pc);

// For many solves with a line's matrix (the modal basis's static shapes, a
// solve per dropper and contact-wire node; shift-and-invert for a count of
// modes): on several ranks every rank factorises the whole matrix as
// use_line_cholesky does on one (PCREDUNDANT; each solve gathers its
// right-hand side), where MUMPS's parallel solves took ~10 ms each on 2
// ranks (docs/benchmarks.md, "The modes on several ranks"); each rank then
// holds what one rank would. On one rank use_line_cholesky. No inertia.
// Options still win.
void use_line_cholesky_on_every_rank(PC pc);

// Krylov-Schur spectrum slicing of the GHEP K x = lambda M x over
// [lambda_lo, lambda_hi], shift-and-invert with use_line_cholesky (its
// inertia), the basis as separate vectors; tolerance 1e-12. On several
// ranks each rank slices a part of the interval with a factorisation of its
// own (SLEPc's partitions, one a rank). The caller sets the operators and
// calls EPSSetFromOptions.
void configure_slicing(EPS eps, double lambda_lo, double lambda_hi);

// The parts of the interval configure_slicing slices at once on comm: the
// option <prefix>eps_krylovschur_partitions, else one a rank. A value that
// is not an integer from 1 to the ranks is InputError naming the option
// (the commands check it before any work: app/inputs.cpp).
int slicing_parts(MPI_Comm comm, const char* prefix);

// The converged eigenvalues of a solved EPS (real parts) and their indices
// in ascending order of eigenvalue.
struct ConvergedSpectrum {
  std::vector<double> lambdas;  // by EPS index
  std::vector<PetscInt> order;  // EPS indices, smallest eigenvalue first
};
ConvergedSpectrum converged_spectrum(EPS eps);

}  // namespace pcsim::solvers
