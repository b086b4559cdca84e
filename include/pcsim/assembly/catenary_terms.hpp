// Terms of the finite-element catenary (thesis 3.1, 3.3): cable forces
// (nonlinear ANCF or linearised), bar forces with dropper slackening,
// inertia and Rayleigh damping. See term.hpp for the interface.
#pragma once

#include <Eigen/Core>
#include <map>
#include <vector>

#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/term.hpp"

namespace pcsim::assembly {

// Full nonlinear ANCF cable forces, gravity, springs (eqs. 3.5-3.8).
class NonlinearCableForces : public Term {
 public:
  explicit NonlinearCableForces(FECatenary& catenary) : catenary_(catenary) {}
  std::string name() const override { return "cable forces (nonlinear ANCF)"; }
  TangentKind tangent_kind() const override { return TangentKind::varying; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  double energy(const CoupledState& state) const override;

 private:
  FECatenary& catenary_;
};

// Cables, gravity and springs linearised about the static configuration U0:
// f ~ b0 + K0 (U - U0). Energy b0.dU + 1/2 dU.K0 dU.
class LinearisedCableForces : public Term {
 public:
  explicit LinearisedCableForces(FECatenary& catenary);
  ~LinearisedCableForces() override;
  std::string name() const override { return "cable forces (linearised)"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  std::vector<LinearPart> linear_parts() const override {
    return {{K0_, 1.0, 0.0, 0.0, SUBSET_NONZERO_PATTERN}};
  }
  void add_residual(const CoupledState& state, Vec F) override;
  double energy(const CoupledState& state) const override;

 private:
  FECatenary& catenary_;
  Mat K0_;
  Vec b0_, work_ = nullptr, work2_ = nullptr;
};

// Axial bars (droppers, steady arms, stitch wires; thesis 3.1.2), with their
// slack criteria when dropper slackening is on. On the cheap path the bars'
// tangents are frozen in J0; a bar that switches between taut and slack
// changes its 3x3 tangent block dK3 (B (x) dK3, B = [1 -1; -1 1]), given as
// up to three rank-one terms (eigenpairs of dK3) frozen at the switch, as a
// refactorisation there would be. More than kMaxSwitched switched bars ask
// for a new J0. The geometric stiffness of a bar that stays taut changes
// little with the state and is not followed (Newton still converges to the
// same residual tolerance).
class BarForces : public Term {
 public:
  static constexpr std::size_t kMaxSwitched = 12;
  BarForces(FECatenary& catenary, bool slack);
  std::string name() const override { return slack_ ? "bars with dropper slack" : "bars"; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  void append_low_rank_sums(const CoupledState& state, std::vector<double>& local) const override;
  void take_low_rank_sums(const double* sums) override;
  std::vector<double> checkpoint() const override;  // the frozen switch terms
  void restore(const std::vector<double>& state) override;
  double energy(const CoupledState& state) const override;

 private:
  std::vector<char> bar_states() const;          // taut (1) / slack (0) per slack bar, all ranks
  std::vector<char> local_bar_states() const;    // the same, on the owner rank only (else 0)
  Eigen::Matrix3d tangent_block(int bar) const;  // at the loaded state
  std::vector<RankOne> switch_terms(std::size_t i) const;
  FECatenary& catenary_;
  bool slack_;
  unsigned parts_;                                 // CatenarySystem terms it assembles
  std::vector<int> slack_bars_;                    // bars with a slack criterion (slack on)
  std::vector<char> reference_states_;             // their state in J0
  std::vector<Eigen::Matrix3d> reference_blocks_;  // their 3x3 block in J0 (owner rank)
  struct Frozen {
    char state = 0;
    std::vector<RankOne> terms;
  };
  std::map<std::size_t, Frozen> frozen_;  // switched bars, by index in slack_bars_
  std::vector<char> summed_states_;       // bar_states() from the system's reduction
};

// Inertia M A (consistent cable masses, lumped bar and point masses).
class Inertia : public Term {
 public:
  explicit Inertia(FECatenary& catenary) : catenary_(catenary), M_(catenary.mass_matrix()) {}
  std::string name() const override { return "inertia"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  std::vector<LinearPart> linear_parts() const override {
    return {{M_, 0.0, 0.0, 1.0, SUBSET_NONZERO_PATTERN}};
  }
  double energy(const CoupledState& state) const override;  // 1/2 V.M V

 private:
  FECatenary& catenary_;
  Mat M_;
};

// Rayleigh damping C V, C = alpha M + beta K_static (thesis eq. 3.1): with
// linearised cables beta K_static = beta K0 + beta K_bars, so that K0 and M
// each carry one product per residual.
class RayleighDamping : public Term {
 public:
  RayleighDamping(FECatenary& catenary, const contact::InteractionEffects& effects);
  std::string name() const override { return "Rayleigh damping"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  std::vector<LinearPart> linear_parts() const override { return parts_; }
  TermPower power(const CoupledState& state) const override;  // -V.C V

 private:
  std::vector<LinearPart> parts_;
};

// Linear dashpots from nodes to the ground (mesh.dashpots: the matched ends
// of a moving window, catenary/window.hpp): F += C V, C diagonal with each
// dashpot's coefficient on its DOF; tangent v C. Dissipates V.C V.
class NodeDashpots : public Term {
 public:
  explicit NodeDashpots(FECatenary& catenary);
  ~NodeDashpots() override;
  std::string name() const override { return "node dashpots"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  std::vector<LinearPart> linear_parts() const override {
    return {{C_, 0.0, 1.0, 0.0, SUBSET_NONZERO_PATTERN}};
  }
  TermPower power(const CoupledState& state) const override;  // -V.C V

 private:
  Mat C_ = nullptr;
};

// Penalty pins (mesh.pins) holding released window ends at their static
// position while the mesh marks them active (the run switches them between
// steps and rebuilds J0; catenary/window.hpp): F += k (u - u_static), tangent
// k, energy 1/2 k (u - u_static)^2.
class NodePins : public Term {
 public:
  explicit NodePins(FECatenary& catenary) : catenary_(catenary) {}
  std::string name() const override { return "node pins"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  double energy(const CoupledState& state) const override;

 private:
  // Calls f(local row, global row, stiffness, static value) for every active
  // pin owned here.
  template <class F>
  void for_owned_active(F f) const;
  FECatenary& catenary_;
};

}  // namespace pcsim::assembly
