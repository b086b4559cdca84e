// Time integration of the pantograph alone (PETSc TS): RK4 and HHT against the exact
// response of the linear two-mass model, RK4 against HHT on the nonlinear DSA-380, and
// the energy balance (thesis 2.3.1) with RK4 at dt = 1e-3 s.
#include <gtest/gtest.h>

#include <cmath>

#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/lumped.hpp"
#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/solvers/pantograph_time.hpp"

using namespace pcsim::pantograph;
using namespace pcsim::scene;
using namespace pcsim::solvers;

namespace {
const std::string kModels = std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/";

// Exact response of M q̈ + C q̇ + K q = Q − F e0 from rest at q0 (constant load).
Eigen::VectorXd exact_lumped(const LumpedPantograph& m, const Eigen::VectorXd& q0, double F,
                             double t) {
  const int n = m.dof_count();
  Eigen::VectorXd load = m.load();
  load[0] -= F;
  const Eigen::VectorXd qeq = m.stiffness().lu().solve(load);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  const Eigen::MatrixXd Minv = m.mass().inverse();
  S.topRightCorner(n, n).setIdentity();
  S.bottomLeftCorner(n, n) = -Minv * m.stiffness();
  S.bottomRightCorner(n, n) = -Minv * m.damping();
  Eigen::EigenSolver<Eigen::MatrixXd> es(S);
  const Eigen::MatrixXcd V = es.eigenvectors();
  Eigen::VectorXcd y0 = Eigen::VectorXcd::Zero(2 * n);
  y0.head(n) = (q0 - qeq).cast<std::complex<double>>();
  const Eigen::VectorXcd c = V.fullPivLu().solve(y0);
  Eigen::VectorXcd e(2 * n);
  for (int k = 0; k < 2 * n; ++k) e[k] = std::exp(es.eigenvalues()[k] * t) * c[k];
  return qeq + (V * e).head(n).real();
}
}  // namespace

TEST(PantographTime, LumpedStepMatchesExactSolution) {
  auto base = load_pantograph_model(kModels + "en50318_two_mass.yaml", nullptr, 0.0);
  auto& m = dynamic_cast<LumpedPantograph&>(*base);
  const Eigen::VectorXd q0 = m.static_equilibrium(0.0, 5.3);  // unloaded, then 120 N step
  const Eigen::VectorXd v0 = Eigen::VectorXd::Zero(2);
  const ForceHistory step = [](double) { return 120.0; };
  for (const char* scheme : {"rk4", "hht"}) {
    TimeOptions opt;
    opt.scheme = scheme;
    opt.dt = 1e-3;
    opt.t_end = 1.0;
    opt.hht_alpha = 0.0;  // trapezoidal rule: second order, no numerical damping
    const auto h = integrate_pantograph(m, q0, v0, step, opt);
    ASSERT_GE(h.t.size(), 1000u);
    EXPECT_NEAR(h.t.back(), 1.0, 1e-12);
    double err = 0, amp = 0;
    for (size_t k = 0; k < h.t.size(); ++k) {
      const Eigen::VectorXd ex = exact_lumped(m, q0, 120.0, h.t[k]);
      err = std::max(err, (h.q[k] - ex).cwiseAbs().maxCoeff());
      amp = std::max(amp, (ex - q0).cwiseAbs().maxCoeff());
    }
    // RK4: O(dt⁴); trapezoidal: O(dt²) with (ω dt)² ≈ 1e-3 for the 3.8 Hz head mode.
    EXPECT_LT(err / amp, std::string(scheme) == "rk4" ? 1e-9 : 2e-3) << scheme;
  }
}

TEST(PantographTime, Dsa380EnergyBalanceRk4) {
  auto model = load_pantograph_model(kModels + "dsa380_rigid.yaml", nullptr, 0.0);
  const Eigen::VectorXd q0 = model->static_equilibrium(120.0, 1.2);
  TimeOptions opt;
  opt.dt = 1e-3;
  opt.t_end = 2.0;
  const auto h = integrate_pantograph(
      *model, q0, Eigen::VectorXd::Zero(4),
      [](double t) { return 120.0 + 30.0 * std::sin(4 * M_PI * t); }, opt);
  const auto b = h.energy_balance();
  double bmax = 0, emin = 1e300, emax = -1e300;
  for (size_t k = 0; k < b.size(); ++k) {
    bmax = std::max(bmax, std::abs(b[k]));
    emin = std::min(emin, h.kinetic[k] + h.potential[k]);
    emax = std::max(emax, h.kinetic[k] + h.potential[k]);
  }
  EXPECT_GT(emax - emin, 1.0);                 // the force does work
  EXPECT_LT(h.work_dissipative.back(), -0.1);  // the damper dissipates
  EXPECT_LT(bmax / (emax - emin), 1e-4) << "balance " << bmax << " range " << emax - emin;
}

TEST(PantographTime, Dsa380HhtAgreesWithRk4) {
  auto model = load_pantograph_model(kModels + "dsa380_rigid.yaml", nullptr, 0.0);
  const Eigen::VectorXd q0 = model->static_equilibrium(0.0, 1.2);
  const ForceHistory step = [](double) { return 120.0; };
  TimeOptions rk, hht;
  rk.t_end = hht.t_end = 1.0;
  rk.dt = 1e-3;
  hht.scheme = "hht";
  hht.dt = 2.5e-4;
  hht.hht_alpha = 0.05;
  hht.record_every = 4;
  const auto a = integrate_pantograph(*model, q0, Eigen::VectorXd::Zero(4), step, rk);
  const auto b = integrate_pantograph(*model, q0, Eigen::VectorXd::Zero(4), step, hht);
  ASSERT_EQ(a.t.size(), b.t.size());
  double err = 0, lo = 1e9, hi = -1e9;
  for (size_t k = 0; k < a.t.size(); ++k) {
    ASSERT_NEAR(a.t[k], b.t[k], 1e-9);
    err = std::max(err, std::abs(a.q[k][2] - b.q[k][2]));
    lo = std::min(lo, a.q[k][2]);
    hi = std::max(hi, a.q[k][2]);
  }
  EXPECT_GT(hi - lo, 1e-3);  // the head moves
  EXPECT_LT(err / (hi - lo), 1e-2) << err << " of " << hi - lo;
}
