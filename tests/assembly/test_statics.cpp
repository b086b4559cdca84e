// Static configuration of simple structures against analytic solutions, the
// assembled tangent against finite differences, and the modes of a taut
// string against the tensioned-beam formula.
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscsnes.h>

#include <cmath>
#include <set>
#include <utility>

#include "catenary_fixtures.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/modes.hpp"
#include "pcsim/solvers/statics.hpp"

using namespace pcsim;

namespace {

// Elastic catenary with linear constitutive law (Irvine): horizontal tension
// H, weight w per unstressed length, unstressed length L0, supports at the
// same level; unstressed arc coordinate s.
struct ElasticCatenary {
  double H, w, EA, L0;
  double V() const { return 0.5 * w * L0; }
  double x(double s) const {
    return H * s / EA + H / w * (std::asinh(V() / H) - std::asinh((V() - w * s) / H));
  }
  double z(double s) const {
    const double T0 = std::hypot(H, V()), Ts = std::hypot(H, V() - w * s);
    return -(V() * s - 0.5 * w * s * s) / EA - (T0 - Ts) / w;
  }
  double span() const { return x(L0); }
  double z_at_x(double xq) const {  // invert x(s) by Newton
    double s = xq / span() * L0;
    for (int it = 0; it < 50; ++it) {
      const double h = 1e-6;
      const double dx = (x(s + h) - x(s - h)) / (2 * h);
      s -= (x(s) - xq) / dx;
    }
    return z(s);
  }
};

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

}  // namespace

TEST(Statics, HeavyCableMatchesElasticCatenary) {
  // EA large, so that Green and engineering strain agree (strain ~ 2e-6).
  const double span = 60, mu = 1.35, g = 9.81, EA = 1e10, H = 20000;
  const int n = 60;
  // Unstressed length that gives horizontal tension H over the span.
  ElasticCatenary cat{H, mu * g, EA, span};
  for (int it = 0; it < 60; ++it) {
    const double h = 1e-7;
    ElasticCatenary c2 = cat;
    c2.L0 += h;
    cat.L0 -= (cat.span() - span) / ((c2.span() - cat.span()) / h);
  }
  const double sag_guess = mu * g * span * span / (8 * H);
  auto mesh = fixtures::single_wire(span, n, mu, EA, 0.0, H, sag_guess, 1.0);
  double ref_total = 0;
  for (auto& e : mesh.cables) ref_total += e.ref_length;
  for (auto& e : mesh.cables) e.unstressed_length = e.ref_length * cat.L0 / ref_total;
  // Weight per unstressed length as the element distributes it.
  cat.w = mu * g * ref_total / cat.L0;

  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Vec x = system.create_vector();
  system.design_state(x);
  auto result = solvers::solve_static(system, x, false);
  ASSERT_TRUE(result.converged);
  const double sag = -cat.z_at_x(0.5 * span);
  double max_err = 0;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const double xi = result.node_values[6 * i], zi = result.node_values[6 * i + 2];
    max_err = std::max(max_err, std::abs(zi - cat.z_at_x(xi)));
  }
  if (system.layout().rank() == 0)
    std::printf("heavy cable: sag %.6f m, max |z - z_analytic| %.3e m (%.2e of sag)\n", sag,
                max_err, max_err / sag);
  EXPECT_LT(max_err, 1e-3 * sag) << "sag " << sag << " m, max error " << max_err << " m";
  VecDestroy(&x);
}

TEST(Statics, AssembledTangentMatchesFiniteDifferences) {
  auto mesh = fixtures::single_wire(20, 8, 1.35, 1.44e7, 195, 20000, 0.05, 0.998);
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Vec x = system.create_vector(), R = system.create_vector(), R2 = system.create_vector(),
      dx = system.create_vector(), JdX = system.create_vector();
  system.design_state(x);
  Mat J = system.layout().create_matrix();
  system.load_state(x);
  MatZeroEntries(J);
  system.assemble_static(R, J);
  MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
  // Directional derivative along a deterministic perturbation.
  PetscInt lo, hi;
  VecGetOwnershipRange(dx, &lo, &hi);
  for (PetscInt i = lo; i < hi; ++i)
    VecSetValue(dx, i, 1e-3 * std::sin(1.7 * i + 0.3), INSERT_VALUES);
  VecAssemblyBegin(dx);
  VecAssemblyEnd(dx);
  MatMult(J, dx, JdX);
  const double h = 1e-4;
  Vec xp;
  VecDuplicate(x, &xp);
  VecWAXPY(xp, h, dx, x);
  system.load_state(xp);
  system.assemble_static(R2, nullptr);
  VecWAXPY(xp, -h, dx, x);
  system.load_state(xp);
  system.assemble_static(R, nullptr);
  VecAXPY(R2, -1.0, R);
  VecScale(R2, 1.0 / (2 * h));
  VecAXPY(R2, -1.0, JdX);
  PetscReal err, ref;
  VecNorm(R2, NORM_2, &err);
  VecNorm(JdX, NORM_2, &ref);
  EXPECT_LT(err / ref, 1e-6);
  VecDestroy(&xp);
  VecDestroy(&x);
  VecDestroy(&R);
  VecDestroy(&R2);
  VecDestroy(&dx);
  VecDestroy(&JdX);
  MatDestroy(&J);
}

TEST(Modes, TautStringMatchesTensionedBeamFormula) {
  // Contact-wire-like string, pinned ends, no gravity, 60 elements of 1 m.
  const double span = 60, mu = 1.35, EA = 1.44e7, EI = 195, T = 20000;
  // Unstressed ratio for axial force T at lambda: EA (lambda^2 - 1)/2 lambda = T.
  double lambda = 1 + T / EA;
  for (int it = 0; it < 30; ++it) {
    const double f = EA * 0.5 * (lambda * lambda - 1) * lambda - T;
    const double df = EA * (1.5 * lambda * lambda - 0.5);
    lambda -= f / df;
  }
  auto mesh = fixtures::single_wire(span, 60, mu, EA, EI, T, 0.0, 1.0 / lambda);
  mesh.gravity.setZero();
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Vec x = system.create_vector();
  system.design_state(x);
  auto statics = solvers::solve_static(system, x, false);
  ASSERT_TRUE(statics.converged);
  auto modes = solvers::compute_modes(system, x, 20, 0.0, false);
  ASSERT_EQ(modes.frequencies_hz.size(), 20u);
  // Transverse modes come in pairs (lateral y, vertical z) of equal frequency.
  for (int n = 1; n <= 10; ++n) {
    const double k = n * M_PI / span;
    const double exact = n / (2 * span) * std::sqrt(T / mu) * std::sqrt(1 + EI / T * k * k);
    for (int pair = 0; pair < 2; ++pair) {
      const double f = modes.frequencies_hz[2 * (n - 1) + pair];
      EXPECT_NEAR(f / exact, 1.0, 5e-3) << "mode " << n << ": " << f << " Hz vs " << exact;
      if (pair == 0 && system.layout().rank() == 0)
        std::printf("taut string mode %d: %.6f Hz, formula %.6f Hz, relative error %.2e\n", n, f,
                    exact, f / exact - 1);
    }
  }
  EXPECT_LT(modes.max_relative_residual, 1e-8);
  VecDestroy(&x);
}

// The consistent mass m_kj (x) I3 stores no exact zero (its cross-component
// entries are not kept) and its product equals the sum of the element
// products, on every rank count.
TEST(MassMatrix, StoresOnlyNonzerosAndEqualsElementSum) {
  auto mesh = fixtures::single_wire(50, 25, 1.35, 1.44e7, 195, 20000, 0.1, 0.999);
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Mat M = system.layout().create_matrix();
  system.assemble_mass(M);
  Vec x = system.create_vector(), Mx = system.create_vector(), sum = system.create_vector();
  PetscInt lo, hi, stored = 0, zeros = 0;
  PCSIM_PETSC(MatGetOwnershipRange(M, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt ncols;
    const PetscScalar* values;
    PCSIM_PETSC(MatGetRow(M, i, &ncols, nullptr, &values));
    stored += ncols;
    for (PetscInt k = 0; k < ncols; ++k) zeros += values[k] == 0.0;
    PCSIM_PETSC(MatRestoreRow(M, i, &ncols, nullptr, &values));
  }
  EXPECT_EQ(zeros, 0);
  for (PetscInt i = lo; i < hi; ++i)
    PCSIM_PETSC(VecSetValue(x, i, std::sin(0.7 * i), INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(x));
  PCSIM_PETSC(VecAssemblyEnd(x));
  PCSIM_PETSC(MatMult(M, x, Mx));
  // The reference: every element's full 12 x 12 matrix, zeros included.
  Vec all;
  VecScatter to_all;
  PCSIM_PETSC(VecScatterCreateToAll(x, &to_all, &all));
  PCSIM_PETSC(VecScatterBegin(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* xa;
  PCSIM_PETSC(VecGetArrayRead(all, &xa));
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[static_cast<std::size_t>(e)];
    const catenary::Mat12 me =
        catenary::cable_mass_matrix(catenary::cable_section(mesh.wires[0], el), el.ref_length);
    PetscInt idx[12];
    system.cable_indices(e, idx);
    for (int r = 0; r < 12; ++r) {
      if (idx[r] < 0) continue;
      double row = 0;
      for (int c = 0; c < 12; ++c)
        if (idx[c] >= 0) row += me(r, c) * xa[idx[c]];
      PCSIM_PETSC(VecSetValue(sum, idx[r], row, ADD_VALUES));
    }
  }
  PCSIM_PETSC(VecRestoreArrayRead(all, &xa));
  PCSIM_PETSC(VecAssemblyBegin(sum));
  PCSIM_PETSC(VecAssemblyEnd(sum));
  PetscReal difference, size;
  PCSIM_PETSC(VecNorm(Mx, NORM_INFINITY, &size));
  PCSIM_PETSC(VecAXPY(sum, -1.0, Mx));
  PCSIM_PETSC(VecNorm(sum, NORM_INFINITY, &difference));
  EXPECT_LT(difference, 1e-14 * size);  // the same sums in another order: round-off only
  // Exactly the positions where some element has a nonzero entry (a third
  // of the element pattern: the rest couples different components).
  std::set<std::pair<PetscInt, PetscInt>> nonzero;
  for (std::size_t e = 0; e < mesh.cables.size(); ++e) {
    const auto& el = mesh.cables[e];
    const catenary::Mat12 me =
        catenary::cable_mass_matrix(catenary::cable_section(mesh.wires[0], el), el.ref_length);
    PetscInt idx[12];
    system.cable_indices(static_cast<int>(e), idx);
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c)
        if (idx[r] >= lo && idx[r] < hi && idx[c] >= 0 && me(r, c) != 0.0)
          nonzero.insert({idx[r], idx[c]});
  }
  EXPECT_EQ(stored, static_cast<PetscInt>(nonzero.size()));
  PCSIM_PETSC(VecScatterDestroy(&to_all));
  for (Vec* v : {&all, &x, &Mx, &sum}) VecDestroy(v);
  MatDestroy(&M);
}

TEST(RankIndependence, StaticAndModesEqualSerial) {
  // The same problem on all ranks of PETSC_COMM_WORLD and on PETSC_COMM_SELF.
  auto mesh = fixtures::single_wire(60, 40, 1.35, 1.44e7, 195, 20000, 0.25, 0.9975);
  std::vector<double> values[2], freqs[2];
  MPI_Comm comms[2] = {PETSC_COMM_WORLD, PETSC_COMM_SELF};
  for (int k = 0; k < 2; ++k) {
    assembly::CatenarySystem system(comms[k], mesh);
    Vec x = system.create_vector();
    system.design_state(x);
    auto statics = solvers::solve_static(system, x, false);
    ASSERT_TRUE(statics.converged);
    values[k] = statics.node_values;
    freqs[k] = solvers::compute_modes(system, x, 20, 0.0, false).frequencies_hz;
    VecDestroy(&x);
  }
  double scale = 0;
  for (double v : values[1]) scale = std::max(scale, std::abs(v));
  EXPECT_LT(max_abs_diff(values[0], values[1]), 1e-9 * scale);
  ASSERT_EQ(freqs[0].size(), freqs[1].size());
  for (std::size_t i = 0; i < freqs[0].size(); ++i)
    EXPECT_NEAR(freqs[0][i] / freqs[1][i], 1.0, 1e-9) << "mode " << i;
}
