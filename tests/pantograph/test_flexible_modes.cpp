// Modes of the flexible-bar DSA-380 about its static equilibrium under 120 N at 1.2 m
// (prestressed tangent), against the rigid model, under mesh refinement, and the bending
// modes of bars 5 and 4 against thesis Table 2.2. Prints the table of
// docs/pantograph.md (run: build/tests/pantograph_test_flexible_modes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcsim/pantograph/flexible_dsa380.hpp"
#include "pcsim/pantograph/linear.hpp"
#include "pcsim/scene/flexible_dsa380_reader.hpp"
#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/solvers/pantograph_modes.hpp"

using namespace pcsim::pantograph;
using pcsim::scene::load_dsa380_parameters;
using pcsim::solvers::damped_modes_slepc;
using pcsim::solvers::undamped_modes_slepc;

namespace {

const std::string kModels = std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/";
// Thesis Table 2.2, flexible model (ANSYS): head rotation, frame, head vertical, head
// horizontal, bending of bar 5, bending of bar 5/4 with the mechanism.
const double kThesisFlexibleHz[6] = {0.77339, 1.2448, 5.6362, 7.777, 21.7733, 25.2445};

struct Analysis {
  FlexibleDsa380Parameters params;
  Eigen::VectorXd q0;
  LinearModel lin;
  std::vector<double> hz;                      // ascending
  Eigen::MatrixXd shapes;                      // M-normalised, one per column
  std::vector<std::array<double, 9>> bending;  // share of ½φᵀKφ in each bar's bending
  std::vector<std::string> dominant;           // coordinate with the largest M_ii φ_i²
  double bar5_axial_force = 0;
};

Analysis analyse(int elements_per_bar) {
  Analysis a;
  a.params = pcsim::scene::read_flexible_dsa380_file(kModels + "dsa380_flexible.yaml");
  a.params.elements.fill(elements_per_bar);
  FlexibleDsa380Pantograph model(a.params, Dsa380Effects{}, 0.0);
  a.q0 = model.static_equilibrium(120.0, 1.2);
  a.lin = linearise(model, a.q0);
  // K is the Hessian of the potential at rest (symmetric to rounding, checked below) and
  // positive definite at the stable equilibrium: the symmetric-definite solver on (M, K),
  // μ = 1/ω², gets the low modes to rounding next to 1e5 Hz ones (on (K, M) it loses
  // eps ω_max²/ω²: 9e-6 on the 0.66 Hz head rotation).
  const Eigen::MatrixXd K = 0.5 * (a.lin.K + a.lin.K.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(a.lin.M, K);
  const int n = static_cast<int>(K.rows());
  a.shapes.resize(n, n);
  const auto names = model.dof_names();
  for (int k = 0; k < n; ++k) {
    const double mu = es.eigenvalues()[n - 1 - k], w2 = 1 / mu;
    a.shapes.col(k) = es.eigenvectors().col(n - 1 - k) / std::sqrt(mu);  // φᵀMφ = 1
    a.hz.push_back(std::sqrt(w2) / (2 * M_PI));
    const auto E = model.bar_strain_energies(a.q0, a.shapes.col(k));
    std::array<double, 9> share{};
    for (int b = 0; b < 9; ++b) share[b] = E[b].bending / (0.5 * w2);
    a.bending.push_back(share);
    Eigen::Index i;
    (a.lin.M.diagonal().array() * a.shapes.col(k).array().square()).maxCoeff(&i);
    a.dominant.push_back(names[i]);
  }
  for (const auto& e : model.mesh().elements) {
    if (e.bar != 5) continue;
    Vector6 qe;
    for (int j = 0; j < 6; ++j) qe[j] = e.dof[j] >= 0 ? a.q0[e.dof[j]] : e.fixed[j];
    a.bar5_axial_force += planar_beam_evaluate(e.beam, qe, false).stress[0] / elements_per_bar;
  }
  return a;
}

LinearModel rigid_linear(Dsa380Pantograph* rigid) {
  return linearise(*rigid, rigid->static_equilibrium(120.0, 1.2));
}

Dsa380Pantograph rigid_model() {
  return Dsa380Pantograph(
      load_dsa380_parameters(pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml")),
      Dsa380Effects{}, 0.0);
}

// First bending mode of bar b (1-based): the lowest mode with most of its strain energy
// (> 50 %) in the bending of that bar.
int first_bending_mode(const Analysis& a, int bar) {
  for (std::size_t k = 0; k < a.hz.size(); ++k)
    if (a.bending[k][bar - 1] > 0.5) return static_cast<int>(k);
  return -1;
}

// The rigid modes mapped onto the flexible coordinates, matched by mass-weighted MAC.
struct RigidMatch {
  int flexible_index;
  double mac, rigid_hz;
};
std::vector<RigidMatch> match_rigid_modes(const Analysis& a) {
  Dsa380Pantograph rigid = rigid_model();
  const auto rigid_modes = undamped_modes_eigen(rigid_linear(&rigid));
  FlexibleDsa380Pantograph flex(a.params, Dsa380Effects{}, 0.0);
  const Eigen::VectorXd& q = a.q0;
  Eigen::MatrixXd J(flex.dof_count(), 4);
  J.col(0) = (flex.rigid_configuration(q[0] + 1e-6, q[1], q[2], q[3]) -
              flex.rigid_configuration(q[0] - 1e-6, q[1], q[2], q[3])) /
             2e-6;
  for (int k = 1; k < 4; ++k) J.col(k) = Eigen::VectorXd::Unit(flex.dof_count(), k);
  std::vector<RigidMatch> out;
  for (const Mode& r : rigid_modes) {
    const Eigen::VectorXd psi = J * r.shape.real();
    RigidMatch best{-1, 0.0, r.frequency_hz};
    for (int k = 0; k < 12; ++k) {
      const Eigen::VectorXd phi = a.shapes.col(k);
      const double c = psi.dot(a.lin.M * phi);
      const double mac = c * c / (psi.dot(a.lin.M * psi) * phi.dot(a.lin.M * phi));
      if (mac > best.mac) best = {k, mac, r.frequency_hz};
    }
    out.push_back(best);
  }
  return out;
}

}  // namespace

TEST(FlexibleDsa380Modes, SlepcAgreesWithTheSymmetricSolver) {
  const Analysis a = analyse(8);
  const double asym = (a.lin.K - a.lin.K.transpose()).cwiseAbs().maxCoeff();
  EXPECT_LT(asym, 1e-15 * a.lin.K.cwiseAbs().maxCoeff());  // measured 5e-17
  // SLEPc (shift-and-invert about ω² = −1 rad²/s², the solver of `pcsim pantograph`)
  // returns every mode, the head rotation and the frame included: a filter on the size of
  // ω² dropped everything below 5.47 Hz here.
  const auto slepc = undamped_modes_slepc(a.lin);
  ASSERT_EQ(slepc.size(), a.hz.size());
  const auto damped = damped_modes_slepc(a.lin);
  ASSERT_EQ(damped.size(), a.hz.size());  // every mode underdamped
  double worst = 0, worst_damped = 0;
  for (int k = 0; k < 7; ++k) {  // the modes below 30 Hz
    worst = std::max(worst, std::abs(slepc[k].frequency_hz / a.hz[k] - 1));
    // Damped natural frequency |λ|/2π: the damper shifts the frame mode by 1e-4.
    worst_damped = std::max(worst_damped, std::abs(damped[k].frequency_hz / a.hz[k] - 1));
  }
  std::printf("SLEPc vs symmetric solver below 30 Hz: undamped %.1e, damped %.1e\n", worst,
              worst_damped);
  // Measured 5.2e-8 (the frame mode; 2e-11 on the head rotation): the two solvers' rounding
  // on a pencil whose ω² span 1e12.
  EXPECT_LT(worst, 2e-7);
  // Measured 9.9e-5 (the frame mode: the damper is not proportional damping).
  EXPECT_LT(worst_damped, 2e-4);
  // With a head restraint the restrained row's constraint removes one mode.
  for (auto restraint :
       {Dsa380Effects::HeadRestraint::rotation, Dsa380Effects::HeadRestraint::horizontal}) {
    Dsa380Effects e;
    e.head_restraint = restraint;
    FlexibleDsa380Pantograph model(a.params, e, 0.0);
    const LinearModel lin = linearise(model, model.static_equilibrium(120.0, 1.2));
    EXPECT_EQ(undamped_modes_slepc(lin).size(), a.hz.size() - 1);
    EXPECT_EQ(damped_modes_slepc(lin).size(), a.hz.size() - 1);
  }
}

TEST(FlexibleDsa380Modes, RigidLikeModesMatchTheRigidModel) {
  const Analysis a = analyse(8);
  const auto match = match_rigid_modes(a);
  ASSERT_EQ(match.size(), 4u);
  const char* name[4] = {"head rotation", "frame", "head vertical", "head horizontal"};
  for (int r = 0; r < 4; ++r) {
    const double f = a.hz[match[r].flexible_index];
    std::printf("rigid mode %d (%s) %.4f Hz -> flexible mode %d, %.4f Hz (%+.2f %%), MAC %.4f\n",
                r + 1, name[r], match[r].rigid_hz, match[r].flexible_index + 1, f,
                100 * (f / match[r].rigid_hz - 1), match[r].mac);
    // The flexible model's first four modes are the rigid ones, in the same order.
    EXPECT_EQ(match[r].flexible_index, r);
    EXPECT_GT(match[r].mac, 0.95);  // measured ≥ 0.98
    // Measured: 0.00, −0.45, −2.80, −1.06 %; head vertical is softened most, by bar 4's
    // bending in series with the head springs. Criterion of issue 13: within 5 %.
    EXPECT_LT(std::abs(f / match[r].rigid_hz - 1), 0.05) << name[r];
  }
}

TEST(FlexibleDsa380Modes, FrequenciesConvergeUnderMeshRefinement) {
  const Analysis a4 = analyse(4), a8 = analyse(8), a16 = analyse(16);
  std::printf("mode   n=4 (Hz)    n=8 (Hz)   n=16 (Hz)  |8-4|/8   |16-8|/16  order\n");
  for (int k = 0; k < 7; ++k) {
    const double d48 = std::abs(a8.hz[k] - a4.hz[k]) / a8.hz[k];
    const double d816 = std::abs(a16.hz[k] - a8.hz[k]) / a16.hz[k];
    const double order = std::log2((a4.hz[k] - a8.hz[k]) / (a8.hz[k] - a16.hz[k]));
    std::printf("%4d %11.5f %11.5f %11.5f  %.2e  %.2e  %5.2f  %s\n", k + 1, a4.hz[k], a8.hz[k],
                a16.hz[k], d48, d816, k < 4 ? 0.0 : order, a16.dominant[k].c_str());
    // Rigid-like modes (1–4): measured |16−8|/16 = 4.9e-10, 2.1e-6, 1.4e-5, 1.4e-6 (the
    // bars' bending enters them a little, most the head vertical mode through bar 4).
    // Bending modes (5–7: bars 4, 5, 2)
    // converge as n⁻² (linear translational mass, planar_beam.hpp): measured order 1.81,
    // 2.02, 2.02 and |16−8|/16 ≤ 1.03 %, so n = 8 (the model file's default) is within
    // ~1.4 % of the converged values and n = 16 within ~0.35 %.
    EXPECT_LT(d816, k < 4 ? 5e-5 : 1.5e-2) << k + 1;
    if (k >= 4) EXPECT_NEAR(order, 2.0, 0.35) << k + 1;
  }
}

TEST(FlexibleDsa380Modes, BendingModesOfBars5And4AgainstThesisTable22) {
  const Analysis a = analyse(16);
  const int m5 = first_bending_mode(a, 5), m4 = first_bending_mode(a, 4);
  ASSERT_GE(m5, 0);
  ASSERT_GE(m4, 0);
  // Bar 5 (upper guide rod) is pinned at both ends: Euler–Bernoulli f = (π/L)²/(2π)
  // √(EI/ρA) √(1 + N L²/(π² EI)) with its axial force N at the equilibrium.
  const TubeSection t5 = flexible_dsa380_sections(a.params)[4];
  const double E = a.params.youngs_modulus, rho = a.params.density;
  const double EI5 = E * t5.second_moment, L5 = t5.length;
  const double f5 = std::pow(M_PI / L5, 2) / (2 * M_PI) * std::sqrt(EI5 / (rho * t5.area)) *
                    std::sqrt(1 + a.bar5_axial_force * L5 * L5 / (M_PI * M_PI * EI5));
  // Bar 4 (upper arm) bends as a cantilever from the knee with bar 6 (head support) at its
  // tip: ω² = 3EI/L³ / (m6 + 0.24 m4).
  const TubeSection t4 = flexible_dsa380_sections(a.params)[3];
  const double m6 = a.params.rigid.m[5];
  const double f4 =
      std::sqrt(3 * E * t4.second_moment / std::pow(t4.length, 3) / (m6 + 0.2357 * t4.mass)) /
      (2 * M_PI);
  std::printf(
      "bar 5 bending: mode %d, %.3f Hz (bending share %.2f); pinned-pinned estimate "
      "%.3f Hz (N = %.1f N); thesis 21.77 Hz (%+.1f %%)\n",
      m5 + 1, a.hz[m5], a.bending[m5][4], f5, a.bar5_axial_force,
      100 * (a.hz[m5] / kThesisFlexibleHz[4] - 1));
  std::printf(
      "bar 4 bending: mode %d, %.3f Hz (bending share %.2f, bar 3 %.2f); tip-mass "
      "cantilever estimate %.3f Hz; thesis 25.24 Hz (%+.1f %%)\n",
      m4 + 1, a.hz[m4], a.bending[m4][3], a.bending[m4][2], f4,
      100 * (a.hz[m4] / kThesisFlexibleHz[5] - 1));
  // Measured: bar 5 at 24.63 Hz, 4.6 % above the isolated pinned–pinned bar (the coupling
  // with the 15 Hz mode below pushes it up; ~0.3 % is mesh error); bar 4 at 15.30 Hz,
  // 6.4 % below the cantilever estimate (the knee lever 3 and rod 2 give at the root).
  EXPECT_GT(a.bending[m5][4], 0.9);
  EXPECT_GT(a.bending[m4][3], 0.5);
  EXPECT_NEAR(a.hz[m5] / f5, 1.046, 0.02);
  EXPECT_NEAR(a.hz[m4] / f4, 0.936, 0.03);
  // Table of docs/pantograph.md (flexible-bar DSA-380).
  Dsa380Pantograph rigid = rigid_model();
  const auto rigid_hz = undamped_modes_eigen(rigid_linear(&rigid));
  const Analysis a8 = analyse(8);
  std::printf(
      "\n| mode | motion (dominant coordinate) | rigid | flexible n=8 | flexible n=16 |"
      " thesis flexible | thesis rigid |\n");
  const double thesis_rigid[4] = {0.6551, 1.2439, 5.6231, 7.8705};
  for (int k = 0; k < 7; ++k) {
    std::printf("| %d | %s | %s | %.4f | %.4f | ", k + 1, a.dominant[k].c_str(),
                k < 4 ? std::to_string(rigid_hz[k].frequency_hz).c_str() : "-", a8.hz[k], a.hz[k]);
    std::printf("%s | %s |\n", k < 4 ? std::to_string(kThesisFlexibleHz[k]).c_str() : "",
                k < 4 ? std::to_string(thesis_rigid[k]).c_str() : "-");
  }
}
