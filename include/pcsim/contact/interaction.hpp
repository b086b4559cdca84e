// Dynamic pantograph-catenary interaction (thesis 3.2-3.3).
//
// One second-order system: the distributed catenary DOFs followed by the DOFs
// of every pantograph (owned by the last rank). Its residual
//   F(t, U, V, A) = M A + C V + f(U) - f_ext(t) + f_contact(U)
// and tangent dF/dU + v dF/dV + a dF/dA are given to a PETSc TS through
// TSSetI2Function/TSSetI2Jacobian, so any second-order TS integrates it; the
// project's own is `-ts_type hht` (thesis 3.3.2).
//
// Effects (each switched on by the scene, costing nothing when off):
//  - catenary geometric nonlinearity: full ANCF forces, or cables linearised
//    about the static configuration (constant K0);
//  - dropper slackening (the bars' slack criteria), else linear droppers;
//  - Rayleigh damping C = alpha M + beta K_static (thesis eq. 3.1);
//  - pantograph effects (friction, damper, restraints, aerodynamics) inside
//    each pantograph model.
// Penalty contact (eqs. 3.9-3.13) acts only in compression; the contact
// element is found each step from x_c = x_0 + V t on the static geometry.
//
// Cheap path: when the catenary is linearised and every pantograph model is
// linear, the step matrix without contact, J0, is assembled and factored once
// per time-step size. The contact tangent of pantograph p is the rank-one term
// kH u_p u_p^T (u_p = [S_z; -1] on the contact element and head DOFs), added
// exactly by the Woodbury formula in a PCSHELL:
//   J^-1 r = J0^-1 r - Z (K^-1 + U^T Z)^-1 U^T J0^-1 r,   Z = J0^-1 U,
// so Newton stays exact for contact at one extra solve per pantograph and
// step (Z_p is combined from cached solves J0^-1 e_g of the contact
// element's DOFs, so a new solve is needed only when the contact enters a new
// element). A dropper that switches between taut and slack is the rank-one
// change of its tangent B (x) dK3 (B = [1 -1; -1 1], dK3 its 3x3 block: up
// to three rank-one terms) and joins the same correction, so J0 is
// refactored only when the time step changes (or more than 24 terms pile up).
// The inner solver takes options with the prefix -cheap_ (e.g.
// -cheap_pc_factor_mat_solver_type mumps).
#pragma once

#include <petscts.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/pantograph/model.hpp"

namespace pcsim::contact {

struct InteractionEffects {
  bool catenary_nonlinear = false;
  bool dropper_slack = true;
  bool rayleigh_damping = true;
};

struct PantographRun {
  std::string name;
  std::unique_ptr<pantograph::PantographModel> model;
  double start_x = 0;         // contact point x at t = 0 [m]
  double speed = 0;           // [m/s]
  double static_force = 0;    // F0: static contact force [N]
  bool static_start = false;  // start in static equilibrium in contact
  double ramp_distance = 0;   // ramp-up: head force weighted 0 -> 1 over this distance [m]
  // Height of the contact point above the pantograph's base at the start [m];
  // <= 0: the model takes absolute heights (lumped models).
  double working_height = 0;
};

// Locates x along the contact wire on a fixed (static) geometry.
class ContactWireLocator {
 public:
  ContactWireLocator(const catenary::CatenaryMesh& mesh, const std::vector<double>& node_values);
  // Element index (into mesh.cables) and local chi of the point at x; false if outside.
  bool locate(double x, int& element, double& chi) const;
  double x_min() const { return x_begin_; }
  double x_max() const { return x_end_; }

 private:
  const catenary::CatenaryMesh& mesh_;
  std::vector<int> elements_;              // contact-wire elements in order
  std::vector<double> node_x_;             // x of their first nodes, then the last node
  std::vector<std::array<double, 12>> q_;  // static element DOFs
  double x_begin_ = 0, x_end_ = 0;
  mutable int last_ = 0;
};

struct StepRecord {
  double t = 0;
  std::vector<double> contact_force, contact_x, wire_z;  // per pantograph
  std::vector<std::vector<double>> q;                    // per pantograph
  std::vector<double> support_z;                         // contact wire at supports
  std::vector<double> dropper_force;                     // every dropper
};

class InteractionProblem {
 public:
  InteractionProblem(MPI_Comm comm, catenary::CatenaryMesh mesh,
                     std::vector<double> static_node_values, std::vector<PantographRun> pantographs,
                     InteractionEffects effects, double contact_stiffness);
  ~InteractionProblem();

  assembly::CatenarySystem& system() { return *system_; }
  const std::vector<PantographRun>& pantographs() const { return pantographs_; }
  bool cheap_path() const { return cheap_path_; }
  void set_cheap_path(bool on) { cheap_path_ = on; }

  // Initial state (static start or ramp, see PantographRun) into U0, V0.
  void initial_state(Vec U0, Vec V0);
  // TS ready to integrate (type from options, default "hht"), I2 callbacks set.
  TS create_ts(double dt, double duration);
  // Measured quantities at state U (collective; filled on rank 0).
  StepRecord record(double t, Vec U);

  // Residual and Jacobian (public for tests and -snes_test_jacobian).
  void residual(double t, Vec U, Vec V, Vec A, Vec F);
  void jacobian(double t, Vec U, Vec V, Vec A, double shift_v, double shift_a, Mat J);
  Mat create_matrix() const;  // the fixed pattern of the coupled system
  Vec create_vector() const { return system_->create_vector(); }
  PetscInt pantograph_first_dof(std::size_t p) const { return panto_first_[p]; }
  // Newton iterations of the coupled static start (0 for a ramp start).
  PetscInt start_iterations() const { return start_iterations_; }

  // Mechanical energy E = T + V of the coupled system at time t (t fixes the
  // contact points and the ramp), for energy-balance tests. Collective.
  // Needs the linearised catenary (throws SolverError if catenary_nonlinear).
  //   T = 1/2 V^T M V (catenary) + sum of the pantographs' kinetic_energy;
  //   V = b0^T dU + 1/2 dU^T K0 dU, dU = U - U0 (linearised cables, gravity,
  //       support springs: the potential of the terms residual() uses)
  //     + sum over bars of bar_strain_energy (droppers with their slack law)
  //     + sum over pantographs of potential_energy(q) - Q_ext . q, with Q_ext the
  //       constant external generalised force (uplift, bellows torque,
  //       aerodynamic force), read from power().external; + (1 - ramp) F0 q_c
  //     + 1/2 kH gap^2 at every contact point in compression.
  // Rayleigh damping, pantograph dampers and friction are not potentials:
  // with them E decreases by their dissipated work.
  double energy(double t, Vec U, Vec V);

 private:
  struct ContactState;
  void load_pantograph_state(Vec U, Vec V, Vec A);
  // q, q', q'' of pantograph p from the last loaded state.
  struct PantographState {
    Eigen::VectorXd q, qd, qdd;
  };
  PantographState pantograph_state(std::size_t p) const;
  double ramp_factor(const PantographRun& p, double t) const;
  // Contact of pantograph p at time t (thesis 3.9-3.13): evaluated only on the
  // rank that owns the contact element, from the last loaded state.
  struct ContactPoint {
    double x = 0;            // contact point along the track
    bool on_wire = false;    // x lies on the contact wire
    bool evaluated = false;  // this rank owns the element: the fields below are set
    int element = -1;
    double chi = 0;
    double head_height = 0;
    ContactEvaluation terms;
  };
  ContactPoint contact_point(std::size_t p, double t) const;
  void add_contact(double t, Vec F, Mat J);
  void solve_coupled_static(Vec U0);
  // Cheap path: contact vectors u_p and Z_p = J0^-1 u_p at the state U.

  std::vector<char> bar_states() const;
  Eigen::Matrix3d bar_tangent_block(int bar) const;  // at the loaded state
  static PetscErrorCode woodbury_setup(PC pc);
  static PetscErrorCode woodbury_apply(PC pc, Vec r, Vec x);

  std::unique_ptr<assembly::CatenarySystem> system_;
  std::vector<double> static_values_;
  std::vector<PantographRun> pantographs_;
  std::vector<PetscInt> panto_first_;
  std::vector<double> head_offset_;  // extra offset so that contact height = q_c + offset
  InteractionEffects effects_;
  double kH_ = 50000;
  bool cheap_path_ = false;
  std::unique_ptr<ContactWireLocator> locator_;
  // Constant matrices: M, K0 (linearised cables and loads) and C_ = the part
  // of beta K that K0 does not hold (Rayleigh C = alpha M + beta K).
  Mat M_ = nullptr, C_ = nullptr, K0_ = nullptr;
  double rayleigh_alpha_ = 0, rayleigh_beta_ = 0;
  Vec U0_ = nullptr, b0_ = nullptr, work_ = nullptr, work2_ = nullptr;
  // Pantograph state on every rank (small): U, V, A per pantograph DOF.
  std::vector<double> panto_u_, panto_v_, panto_a_;
  PetscInt n_panto_dofs_ = 0;
  // Cheap path: shifts of the Jacobian currently assembled.
  double cached_shift_v_ = -1, cached_shift_a_ = -1;
  PetscInt start_iterations_ = 0;
  // Cheap path (Woodbury). A rank-one term c u u^T with z = J0^-1 u.
  struct LowRankTerm {
    Vec u = nullptr, z = nullptr;
    double coefficient = 0;
  };
  KSP inner_ksp_ = nullptr;
  bool inner_factored_ = false;
  bool capacitance_dirty_ = true;
  Eigen::MatrixXd capacitance_;  // K^-1 + U^T Z over the active terms
  std::vector<LowRankTerm*> active_terms_;
  std::vector<int> droppers_;        // dropper bars, in mesh order (records)
  std::vector<int> slack_bars_;      // bars with a slack criterion
  std::vector<char> j0_bar_states_;  // their state (taut 1, slack 0) in J0
  // Bars whose state differs from J0's: up to 3 terms each (eigenpairs of
  // the change of their 3x3 tangent block), keyed by index in slack_bars_.
  std::map<int, std::vector<LowRankTerm>> bar_terms_;
  std::map<int, char> bar_term_state_;            // state the terms were built for
  std::vector<Eigen::Matrix3d> j0_bar_tangents_;  // 3x3 block of each in J0
  std::vector<LowRankTerm> contact_terms_;        // per pantograph
  std::vector<int> contact_element_;              // element and chi u_p was built for
  std::vector<double> contact_chi_;
  std::map<PetscInt, Vec> unit_solutions_;  // J0^-1 e_g of contact DOFs g
  Vec unit_solution(PetscInt g);
  void clear_low_rank();
  bool update_low_rank(double t);  // false: too many terms, J0 must be rebuilt
};

}  // namespace pcsim::contact
