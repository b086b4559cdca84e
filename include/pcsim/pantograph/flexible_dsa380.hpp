// Flexible-bar DSA-380 pantograph (thesis 2.2): the bars of the rigid DSA-380 as planar
// co-rotational beams (planar_beam.hpp), joined as the thesis joins them in its FE model.
//
// Bars (Table 2.1; points as in the rigid model, Annex A):
//   1 lower arm 1→4, 2 lower guide rod 2→3, 3 knee lever 3→4, 4 upper arm 4→5,
//   5 upper guide rod 6→j, 6 head support j→5: beams with n_b elements each, steel tubes
//   with the external radii of Table 2.1 and internal radii from the rigid model's masses
//   by (2.29) m = ρπ(r_ext² − r_int²)L, as the thesis sized them;
//   7 head: the rigid model's head (rigid body m7, I7, LG7 on two springs from point 5);
//   8 bracket 4→6 of bar 1 and 9 damper lever 1→1p of bar 1: massless (thesis 2.2).
// Joints: revolute joints share the translations of the coincident nodes, each bar keeping
// its own rotation; points 1 and 2 are fixed. Bars that are one piece share the rotation
// too: 3–4 at point 4 (the knee lever and the upper arm, angle θ34), and 1–8 at point 4.
// Bar 8 is one element clamped to bar 1 and hinged at point 6 (massless and loaded only at
// its ends, so the cubic of one Euler–Bernoulli element is its exact deflection). Bar 9 is
// taken rigid: it carries only the damper, and a flexible massless lever would put a
// massless (first-order) node in series with the damper, which a model with an invertible
// mass matrix cannot hold; its stiffness in series with c (3EI/L³ ≈ 6.5e8 N/m for Table
// 2.1's tube, 6 cm long) relaxes in c/k ≈ 6e-5 s, far above the modes studied.
//
// q = {θ, x10, y10, θ7, x5, y5, x4, y4, x3, y3, x6, y6, xj, yj, joint rotations, interior
// nodes}: absolute coordinates (m, rad). θ is the rotation of bar 1's section at point 1,
// on which the drive spring kr, the bellows torque M0 and the damper lever act, as θ does
// in the rigid model. Any configuration of the rigid mechanism is stress-free
// (rigid_configuration()).
//
// R = M q̈ + (head inertia terms) + dV/dq + damper + friction − M0 e_θ − F_aero e_y10,
// V = beam strain energy + gravity + ½ kr (θ − θr0)² + head springs; M constant for the
// bars (planar_beam.hpp: linear translational interpolation, lumped rotary inertia), the
// head's rows as in the rigid model (A.36). Restraints and friction as in the rigid model,
// with y5 and x5 now coordinates (v_r = ẏ10 − ẏ5; x10 ≡ x5 replaces the x10 row).
// The uplift characteristic (bellows.hpp) changes the torque by the rigid mechanism's
// ΔM(θ) from the flexible equilibrium's M0 (the bars' deflection changes little with θ).
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "pcsim/core/triplet_pattern.hpp"
#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/planar_beam.hpp"

namespace pcsim::pantograph {

struct FlexibleDsa380Parameters {
  Dsa380Parameters rigid;  // geometry, head, springs, damper, masses of bars 1–7
  double density = 7850;   // ρ (kg/m³), steel
  double youngs_modulus = 2.1e11;
  std::array<double, 9> r_ext{};                  // Table 2.1 external radii (m)
  std::array<double, 2> massless_r_int{};         // bars 8, 9: Table 2.1 internal radii
  std::array<int, 6> elements{8, 8, 8, 8, 8, 8};  // elements of bars 1–6
};

// A bar's tube: length, radii, mass (0 for bars 8, 9), area and second moment of area.
struct TubeSection {
  double length = 0, r_ext = 0, r_int = 0, mass = 0, area = 0, second_moment = 0;
};
// The nine sections; r_int of bars 1–7 solved from (2.29) with the rigid model's masses
// (bar 7 for comparison with Table 2.1 only: the head is the rigid body). Throws
// std::invalid_argument if a mass does not fit in its tube (r_int² < 0).
std::array<TubeSection, 9> flexible_dsa380_sections(const FlexibleDsa380Parameters& p);

// Elements, coordinate names and the map from the rigid mechanism to q.
struct FlexibleDsa380Mesh {
  struct Element {
    PlanarBeamElement beam;
    std::array<int, 6> dof{};  // index in q, or −1 (fixed translation, released rotation)
    Vector6 fixed = Vector6::Zero();
    int bar = 0;  // 1..6, 8
  };
  // Where a coordinate sits on the rigid mechanism: a point (between points a and b at
  // fraction s; x or y), a bar's angle (bar index a: 0..5 bars 1–6, 6 bar 8), or a head
  // coordinate (component 0..2 of x10, y10, θ7).
  struct Source {
    enum class Kind { position, angle, head } kind = Kind::position;
    int a = 0, b = 0, component = 0;
    double s = 0;
  };
  std::vector<Element> elements;
  std::vector<std::string> names;
  std::vector<Source> sources;
  int x5 = -1, y5 = -1;
};
FlexibleDsa380Mesh build_flexible_dsa380_mesh(const FlexibleDsa380Parameters& p,
                                              const std::array<TubeSection, 9>& sections);

class FlexibleDsa380Pantograph : public PantographModel {
 public:
  FlexibleDsa380Pantograph(FlexibleDsa380Parameters params, Dsa380Effects effects,
                           double speed_m_s);

  std::string kind() const override { return "dsa380_flexible"; }
  // The mesh's coordinates and, with the bellows' pressure loop, its state (bellows.hpp).
  int dof_count() const override {
    return static_cast<int>(mesh_.names.size()) + (bellows_.has_state() ? 1 : 0);
  }
  std::vector<std::string> dof_names() const override;
  int contact_dof() const override { return 2; }
  double contact_offset() const override { return p_.rigid.L7p; }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const override;
  void tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const override;
  // The same tangents summed with the shifts, their nonzeros only (about 6 % of
  // the 150 x 150 entries; the cheap path refactors the block with them at
  // every iteration): the entries the beams, head, drive, bellows and
  // restraints write at this state, explicit zeros included.
  bool sparse_step_tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                           const Eigen::VectorXd& qdd, double shift_v, double shift_a,
                           Eigen::SparseMatrix<double>& J) const override;
  bool sparse_mass(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                   Eigen::SparseMatrix<double>& M) const override;
  // M alone (no beam stiffness): the constant bars' mass, the head's and the bellows'.
  void mass(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
            Eigen::Ref<Eigen::MatrixXd> M) const override;
  bool is_linear() const override { return false; }
  // Newton on R(q, 0, 0) + F0 e_y10 = 0 with y10 = h0 − L7p, solving for q and the bellows
  // torque M0 together (prestressed bars), from the rigid model's equilibrium (2.12–2.14).
  // Restrained rows are replaced by their position constraints. Sets M0, returns q0.
  Eigen::VectorXd static_equilibrium(double contact_force, double working_height) override;
  // Heights above the base, as the rigid model: nominal working height 1.2 m.
  double default_working_height() const override { return 1.2; }
  // 100 eps times the stiffest bar's EA/l0 times coordinates of ~2 m (~2e-3 N).
  double static_residual_floor() const override;
  double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  PowerSplit power(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  // Base motion (issue 25, dsa380_base.cpp), as the rigid model: q is measured in the
  // moving frame of the base; g becomes g + a_b(t) in the weights of bars and head.
  bool moving_frame() const override { return true; }
  void set_base_motion(BaseMotion motion) override { frame_.set(std::move(motion), kind()); }
  Eigen::VectorXd base_inertia(const Eigen::VectorXd& q) const override;
  double frame_height(double t) const override { return frame_.height(t); }
  double frame_velocity(double t) const override { return frame_.velocity(t); }

  // q of the undeformed mechanism at frame angle θ with the given head coordinates.
  Eigen::VectorXd rigid_configuration(double theta, double x10, double y10, double theta7) const;
  double bellows_torque() const { return M0_; }
  void set_bellows_torque(double M0) { M0_ = M0; }
  int dof_x5() const { return mesh_.x5; }
  int dof_y5() const { return mesh_.y5; }
  const Bellows& bellows() const { return bellows_; }
  const FlexibleDsa380Parameters& parameters() const { return p_; }
  const std::array<TubeSection, 9>& sections() const { return sections_; }
  const FlexibleDsa380Mesh& mesh() const { return mesh_; }

  // Strain energy of a small displacement dq about q0 per bar (index 0..8 = bars 1–9;
  // 7 and 9 are rigid: 0), split into axial ½ N-part and bending ½ M-part of ½ dεᵀ D dε.
  struct BarEnergy {
    double axial = 0, bending = 0;
  };
  std::array<BarEnergy, 9> bar_strain_energies(const Eigen::VectorXd& q0,
                                               const Eigen::VectorXd& dq) const;

 private:
  // ab: the base's acceleration (0: at rest, as the static equilibrium). K, C
  // and M are written in place (n x n, sized by the caller): the tangents go
  // straight into the caller's storage, no copy of three dense n x n blocks.
  using MatrixRef = Eigen::Ref<Eigen::MatrixXd>;
  void assemble(double ab, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::VectorXd* R, MatrixRef* K, MatrixRef* C,
                MatrixRef* M) const;
  // The parts of R and its tangents; Matrix: MatrixRef, or the sparse step
  // tangent's triplet views (flexible_dsa380.cpp, sparse_step_tangent).
  template <class Matrix>
  void add_beams(const Eigen::VectorXd& q, Eigen::VectorXd* R, Matrix* K) const;
  template <class Matrix>
  void add_head(double ab, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::VectorXd* R, Matrix* K, Matrix* C,
                Matrix* M) const;
  template <class Matrix>
  void add_drive(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd* R, Matrix* K,
                 Matrix* C) const;
  template <class Matrix>
  void apply_restraints(const Eigen::VectorXd& qdd, Eigen::VectorXd* R, Matrix* K, Matrix* C,
                        Matrix* M) const;
  Vector6 gather(const FlexibleDsa380Mesh::Element& e, const Eigen::VectorXd& q) const;
  bool damper_active(const Eigen::VectorXd& qd) const;
  int bellows_dof() const {
    return bellows_.has_state() ? static_cast<int>(mesh_.names.size()) : -1;
  }

  FlexibleDsa380Parameters p_;
  Dsa380Effects e_;
  double speed_ = 0;
  std::array<TubeSection, 9> sections_;
  FlexibleDsa380Mesh mesh_;
  Eigen::MatrixXd bar_mass_;                     // constant mass matrix of the beams
  Eigen::SparseMatrix<double> bar_mass_sparse_;  // the same, for the residual's product
  Eigen::VectorXd bar_weight_;                   // dVg/dq of the beams
  Eigen::VectorXd bar_masses_;  // the same per unit g: the beams' Σ m_i ∂z_i/∂q
  mutable std::vector<Eigen::Triplet<double>> triplets_;  // sparse_step_tangent()'s
  mutable core::TripletPattern tangent_pattern_;          // ... and their kept positions
  MovingFrame frame_;
  double aero_force_ = 0;
  double M0_ = 0;
  Bellows bellows_;  // uplift characteristic: M0 + ΔM(θ) with the rigid mechanism's ΔM
  HeadSpring spring_;
  FrameDamper damper_;
  HeadFriction friction_;
};

}  // namespace pcsim::pantograph
