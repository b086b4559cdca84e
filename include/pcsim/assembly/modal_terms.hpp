// Terms of the modal catenary (assembly/modal_catenary.hpp) over its modal
// coordinates eta (M-orthonormal, K-diagonal basis):
//  - inertia eta'', Rayleigh damping (alpha I + beta Omega^2) eta' and
//    stiffness Omega^2 eta (thesis eq. 3.1 projected), diagonal;
//  - the dropper slack correction (low rank) or every bar's exact nonlinear
//    force minus its linearisation (varying: the all-modes check against FE).
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <vector>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/assembly/term.hpp"
#include "pcsim/catenary/elements.hpp"

namespace pcsim::assembly {

class ModalExactDroppers;

// The modal coordinates' own equations, diagonal (thesis eq. 3.1 projected):
// inertia eta'', Rayleigh damping (alpha + beta omega_k^2) eta_k' (when the
// scene has it) and stiffness omega_k^2 eta_k, in one loop over the modes
// per residual (three terms of one loop each measured 3 us more per step of
// EN 50318; as linear parts with diagonal matrices they cost two sparse
// products and six vector operations per residual). Energy
// 1/2 (|eta'|^2 + eta . Omega^2 eta); power -eta' . (alpha + beta Omega^2) eta'.
// Under a mean wind the damping adds the diagonal of the wires' aerodynamic
// damping in the basis (catenary::ReducedBasis::wind_damping; on the FE
// levels the full matrix, assembly/wind_terms.hpp), whatever the Rayleigh
// damping's switch.
class ModalOscillators : public Term {
 public:
  // damping: the Rayleigh coefficients (alpha, beta), or none.
  ModalOscillators(ModalCatenary& catenary, bool damping, double alpha, double beta);
  std::string name() const override { return "modal oscillators"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  void add_residual(const CoupledState& state, Vec F) override;
  AccelerationUse acceleration_use() const override { return AccelerationUse::constant; }
  void add_inertia(const CoupledState& state, Vec A, Vec F) const override;  // unit mass: F += A
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  double energy(const CoupledState& state) const override;
  TermPower power(const CoupledState& state) const override;

 private:
  ModalCatenary& catenary_;
  Eigen::ArrayXd stiffness_, damping_;  // omega_k^2, alpha + beta omega_k^2 (empty: none)
};

// A slack bar d (dl = s_d + b_d . eta < 0) loses the stiffness the linear
// model gives it: residual -k min(dl, 0) b_d, tangent -k b_d b_d^T while
// slack (rank one, dense u, reuse_columns false); energy -1/2 k min(dl, 0)^2.
// With force_free (catenary.modal.bars: slack_exact) a slack bar of the
// 'force' criterion carries no force at all: it also loses the geometric
// stiffness (N0/l0)(I - e e^T) of its static tension, which the modes hold.
// Two more rank-one terms -g (t_j . eta) t_j^T, t_j the basis row of
// n_j . (u_j - u_i), n_1 and n_2 across its static direction e, g = N0/l0;
// energy -1/2 g (t_j . eta)^2 (docs/fidelity.md, "A slack dropper's
// geometric stiffness"). J0 holds no slack bar: the change is never too
// large for the cheap path.
class ModalDropperSlack : public Term {
 public:
  // force_free: a slack 'force' bar loses its geometric stiffness too (bars: slack_exact).
  // exact: the droppers near the pantographs taken exactly, left out here (may be null).
  ModalDropperSlack(ModalCatenary& catenary, bool force_free,
                    const ModalExactDroppers* exact = nullptr);
  std::string name() const override { return "modal dropper slack"; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState&, Shifts, Mat) override {}
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  double energy(const CoupledState& state) const override;

 private:
  void make_rows();
  // slack_now() less the droppers exact_ covers at the state's time.
  const std::vector<std::size_t>& slack_here(const CoupledState& state) const;

  ModalCatenary& catenary_;
  const ModalExactDroppers* exact_;
  mutable std::vector<std::size_t> slack_here_;  // kept storage
  SharedEntries<PetscInt> modes_;                // 0 .. m-1, shared by every term handed out
  // Tracked bar d's rows b_d, t_1 and t_2 (these two where g > 0), made at construction.
  std::vector<std::array<SharedEntries<double>, 3>> rows_;
  std::vector<double> geometric_;                     // g = N0/l0 per tracked bar, 0: none
  std::vector<Eigen::Matrix<double, 3, 2>> normals_;  // n_1, n_2 per tracked bar
};

// Droppers near the pantographs with their exact force (the modal level
// otherwise linearises them about the static state; docs/fidelity.md,
// "Droppers near the pantographs exact"): for each dropper d within 'reach'
// of a pantograph's contact point, residual R_d^T (f(r) - f0 - K0 r),
// tangent R_d^T (K(r) - K0) R_d, where R_d = (b_d, t_1, t_2) are the rows of
// its ends' relative displacement along its static direction e and across
// it (n_1, n_2), r = R_d eta, f and K the bar's force and tangent at its end
// j in that frame (catenary::bar_internal_force: zero while the dropper is
// shorter than unstressed, as on the FE levels), f0 and K0 the linear
// model's. Such a dropper is not ModalDropperSlack's. The 3 x 3 change D =
// K(r) - K0 goes to the solver as six rank-one terms over fixed rows, b,
// t_1, t_2, b + t_1, b + t_2, t_1 + t_2, whose coefficients alone vary (a
// symmetric 3 x 3 has six entries): J0^-1 u and the capacitance's products
// are kept while a dropper stays in the set. The set depends on the time
// alone (fixed within a step). Energy E(r) - E0 - f0 . r - 1/2 r . K0 r.
class ModalExactDroppers : public Term {
 public:
  // slack: the droppers' slackening is on (dropper_slack).
  ModalExactDroppers(ModalCatenary& catenary, double reach, bool slack);
  std::string name() const override { return "modal droppers near the pantographs (exact)"; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState&, Shifts, Mat) override {}
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  double energy(const CoupledState& state) const override;
  // Tracked bar d (index into ModalCatenary::slack_bars()) is this term's at the state's time.
  bool covers(const CoupledState& state, std::size_t tracked) const;

 private:
  struct Dropper {
    std::size_t tracked;  // index into ModalCatenary::slack_bars()
    double x;             // mid-point along the track [m]
    catenary::BarParameters params;
    catenary::Vec6 q0;
    Eigen::Matrix3d frame;  // columns e, n_1, n_2
    Eigen::Vector3d f0;     // end j's force in the frame at the static state (linear model)
    Eigen::Matrix3d K0;     // end j's tangent in the frame at the static state (linear model)
  };
  // t_1, t_2 and the three sums, made when a dropper enters the set.
  using Rows = std::shared_ptr<const Eigen::Matrix<double, 5, Eigen::Dynamic, Eigen::RowMajor>>;
  bool within_reach(const CoupledState& state, const Dropper& dropper) const;
  // The droppers within reach at the state's time (active_).
  void find_active(const CoupledState& state);
  const Rows& rows(std::size_t i);
  // r = R_d eta (rows(i) made), and end j's force and tangent in the frame at r.
  Eigen::Vector3d relative(std::size_t i) const;
  void force(std::size_t i, const Eigen::Vector3d& r, Eigen::Vector3d& f, Eigen::Matrix3d* K) const;

  ModalCatenary& catenary_;
  double reach_;
  SharedEntries<PetscInt> modes_;
  std::vector<Dropper> droppers_;     // by tracked bar, ascending
  std::map<std::size_t, Rows> rows_;  // by index into droppers_, while in the set
  std::vector<std::size_t> active_;   // indices into droppers_
};

// A moving window's end dashpots (catenary/window.hpp) over the modes:
// residual c_e (phi_e . eta') phi_e^T per dashpot e (phi_e: the basis row of
// its DOF), tangent shift_v c_e phi_e^T phi_e: rank one each, with the
// shift_v of the last reference tangent (J0 holds none of it: the modal J0
// stays diagonal). Power -c_e (phi_e . eta')^2.
class ModalNodeDashpots : public Term {
 public:
  explicit ModalNodeDashpots(ModalCatenary& catenary);
  std::string name() const override { return "modal node dashpots"; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState&, Shifts shifts, Mat) override {
    shift_v_ = shifts.v;
  }
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  TermPower power(const CoupledState& state) const override;

 private:
  ModalCatenary& catenary_;
  SharedEntries<PetscInt> modes_;
  std::map<long, SharedEntries<double>> rows_;  // a dashpot's basis row, made once
  double shift_v_ = 0;
  Eigen::VectorXd rates_;  // the modal part of V (kept storage)
};

// A window's active end pins (mesh.pins, switched by the run between steps):
// residual k (phi_p . eta) phi_p^T, tangent k phi_p^T phi_p (rank one each,
// not in J0). Energy 1/2 k (phi_p . eta)^2.
class ModalNodePins : public Term {
 public:
  explicit ModalNodePins(ModalCatenary& catenary);
  std::string name() const override { return "modal node pins"; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState&, Shifts, Mat) override {}
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  double energy(const CoupledState& state) const override;

 private:
  ModalCatenary& catenary_;
  SharedEntries<PetscInt> modes_;
  std::map<long, SharedEntries<double>> rows_;  // a pin's basis row, made once
};

// Every bar's exact force minus its linearisation at the static state q0:
// residual P^T (f(q) - f(q0) - K(q0) (q - q0)), q = q0 + P eta (P: the rows
// of the bar's ends), tangent P^T (K(q) - K(q0)) P (dense: full path).
class ModalExactBars : public Term {
 public:
  // slack = false: every bar taut (dropper slackening off).
  ModalExactBars(ModalCatenary& catenary, bool slack);
  std::string name() const override { return "modal bars (exact)"; }
  TangentKind tangent_kind() const override { return TangentKind::varying; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  double energy(const CoupledState& state) const override;

 private:
  using Rows6 = Eigen::Matrix<double, 6, Eigen::Dynamic>;
  struct Bar {
    int index;
    Rows6 P;
    Eigen::Matrix<double, 6, 1> q0, f0;
    Eigen::Matrix<double, 6, 6> K0;
    catenary::BarParameters params;
  };
  ModalCatenary& catenary_;
  std::vector<Bar> bars_;
};

}  // namespace pcsim::assembly
