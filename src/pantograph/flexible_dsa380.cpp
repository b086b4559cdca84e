// Flexible DSA-380: residual, exact tangents, energies and power.
#include "pcsim/pantograph/flexible_dsa380.hpp"

#include <algorithm>
#include <cmath>

namespace pcsim::pantograph {

FlexibleDsa380Pantograph::FlexibleDsa380Pantograph(FlexibleDsa380Parameters params,
                                                   Dsa380Effects effects, double speed_m_s)
    : p_(std::move(params)),
      e_(effects),
      speed_(speed_m_s),
      sections_(flexible_dsa380_sections(p_)),
      mesh_(build_flexible_dsa380_mesh(p_, sections_)) {
  const Dsa380Parameters& r = p_.rigid;
  if (e_.aerodynamic)
    aero_force_ = r.aero_a + r.aero_b * speed_m_s + r.aero_c * speed_m_s * speed_m_s;
  bellows_ = Bellows(r.bellows, e_.uplift_characteristic, aero_force_);
  spring_ = head_spring(r);
  damper_ = frame_damper(r, e_);
  friction_ = head_friction(e_);
  const int n = dof_count();
  bar_mass_ = Eigen::MatrixXd::Zero(n, n);
  bar_weight_ = Eigen::VectorXd::Zero(n);
  bar_masses_ = Eigen::VectorXd::Zero(n);
  for (const auto& e : mesh_.elements) {
    const Matrix6 Me = planar_beam_mass(e.beam);
    const Vector6 We = planar_beam_weight(e.beam, r.g), Wm = planar_beam_weight(e.beam, 1.0);
    for (int a = 0; a < 6; ++a) {
      if (e.dof[a] < 0) continue;
      bar_weight_[e.dof[a]] += We[a];
      bar_masses_[e.dof[a]] += Wm[a];
      for (int b = 0; b < 6; ++b)
        if (e.dof[b] >= 0) bar_mass_(e.dof[a], e.dof[b]) += Me(a, b);
    }
  }
  bar_mass_sparse_ = bar_mass_.sparseView(0.0, 0.0);  // exact zeros left out only
}

std::vector<std::string> FlexibleDsa380Pantograph::dof_names() const {
  std::vector<std::string> names = mesh_.names;
  if (bellows_.has_state()) names.push_back("bellows_dM");
  return names;
}

Vector6 FlexibleDsa380Pantograph::gather(const FlexibleDsa380Mesh::Element& e,
                                         const Eigen::VectorXd& q) const {
  Vector6 qe;
  for (int a = 0; a < 6; ++a) qe[a] = e.dof[a] >= 0 ? q[e.dof[a]] : e.fixed[a];
  return qe;
}

bool FlexibleDsa380Pantograph::damper_active(const Eigen::VectorXd& qd) const {
  return e_.damper && damper_.acts(qd[mesh_.y5]);
}

namespace {
// A sparse matrix being assembled as one list of triplets, such as the step
// tangent K + shift_v C + shift_a M: K, C and M are three views of it with
// their weights. An entry takes += and -=, and = where nothing else has
// written it (the bellows' loop row, a restraint's row just zeroed): there it
// adds too. Duplicates are summed when the sparse matrix is formed.
class TripletView {
 public:
  TripletView(std::vector<Eigen::Triplet<double>>& list, double weight)
      : list_(list), weight_(weight) {}
  // weight x a's entries.
  void add(const Eigen::SparseMatrix<double>& a) {
    for (int j = 0; j < a.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it)
        list_.emplace_back(it.row(), it.col(), weight_ * it.value());
  }
  class Entry {
   public:
    Entry(TripletView& view, int i, int j) : view_(view), i_(i), j_(j) {}
    void operator+=(double v) { view_.list_.emplace_back(i_, j_, view_.weight_ * v); }
    void operator-=(double v) { *this += -v; }
    void operator=(double v) { *this += v; }

   private:
    TripletView& view_;
    int i_, j_;
  };
  Entry operator()(int i, int j) { return Entry(*this, i, j); }
  // Every entry of row r so far, of the three views.
  void zero_row(int r) {
    list_.erase(std::remove_if(list_.begin(), list_.end(),
                               [r](const Eigen::Triplet<double>& e) { return e.row() == r; }),
                list_.end());
  }

 private:
  std::vector<Eigen::Triplet<double>>& list_;
  double weight_;
};

void zero_row(Eigen::Ref<Eigen::MatrixXd>& m, int r) {
  m.row(r).setZero();
}
void zero_row(TripletView& m, int r) {
  m.zero_row(r);
}

// Damper length l_a(θ) through the rigid lever 1→1p (bar 9), with d/dθ, d²/dθ² (A.14).
Jet damper_length(const Dsa380Parameters& p, double theta) {
  const Jet th1p = Jet::variable(theta) + Jet(p.theta_1p);
  const Jet dx = Jet(p.x1 - p.x13) + Jet(p.L1p) * cos(th1p);
  const Jet dy = Jet(p.y1 - p.y13) + Jet(p.L1p) * sin(th1p);
  return sqrt(dx * dx + dy * dy);
}
}  // namespace

template <class Matrix>
void FlexibleDsa380Pantograph::add_beams(const Eigen::VectorXd& q, Eigen::VectorXd* R,
                                         Matrix* K) const {
  for (const auto& e : mesh_.elements) {
    const PlanarBeamState s = planar_beam_evaluate(e.beam, gather(e, q), K != nullptr);
    for (int a = 0; a < 6; ++a) {
      const int i = e.dof[a];
      if (i < 0) continue;
      if (R) (*R)[i] += s.force[a];
      if (K)
        for (int b = 0; b < 6; ++b)
          if (e.dof[b] >= 0) (*K)(i, e.dof[b]) += s.stiffness(a, b);
    }
  }
}

template <class Matrix>
void FlexibleDsa380Pantograph::add_head(double ab, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                        Eigen::VectorXd* R, Matrix* K, Matrix* C, Matrix* M) const {
  const Dsa380Parameters& p = p_.rigid;
  const double g = p.g + ab;  // a moving base: g + a_b (dsa380_base.cpp)
  const double m7 = p.m[6], LG7 = p.LG[6], I7 = p.I[6], th7d = qd[3];
  const double s = std::sin(q[3] - p.thetaG[6]), c = std::cos(q[3] - p.thetaG[6]);
  if (R) {  // head rows of (A.36)
    (*R)[1] += m7 * qdd[1] - m7 * LG7 * (s * qdd[3] + c * th7d * th7d);
    (*R)[2] += m7 * qdd[2] + m7 * LG7 * (c * qdd[3] - s * th7d * th7d) + m7 * g - aero_force_;
    (*R)[3] +=
        m7 * LG7 * (c * qdd[2] - s * qdd[1]) + (I7 + m7 * LG7 * LG7) * qdd[3] + m7 * g * LG7 * c;
  }
  if (M) {
    (*M)(1, 1) += m7;
    (*M)(1, 3) += -m7 * LG7 * s;
    (*M)(2, 2) += m7;
    (*M)(2, 3) += m7 * LG7 * c;
    (*M)(3, 1) += -m7 * LG7 * s;
    (*M)(3, 2) += m7 * LG7 * c;
    (*M)(3, 3) += I7 + m7 * LG7 * LG7;
  }
  if (K) {
    (*K)(1, 3) += -m7 * LG7 * (c * qdd[3] - s * th7d * th7d);
    (*K)(2, 3) += m7 * LG7 * (-s * qdd[3] - c * th7d * th7d);
    (*K)(3, 3) += m7 * LG7 * (-s * qdd[2] - c * qdd[1]) - m7 * g * LG7 * s;
    (*C)(1, 3) += -2 * m7 * LG7 * c * th7d;
    (*C)(2, 3) += -2 * m7 * LG7 * s * th7d;
  }
  if (!R && !K) return;
  // Springs from point 5 to the head ends 11, 12 (A.11): l = |P5 − P10 ± (L7/2) e(θ7)|,
  // force f(l) ∇l, tangent f' ∇l∇lᵀ + f ∇²l (3.34); variables {x5, y5, x10, y10, θ7}.
  const int v[5] = {mesh_.x5, mesh_.y5, 1, 2, 3};
  const double half = 0.5 * p.L7, ct7 = std::cos(q[3]), st7 = std::sin(q[3]);
  for (int sp = 0; sp < 2; ++sp) {
    const double sigma = sp == 0 ? 1.0 : -1.0;
    const Eigen::Vector2d d(q[mesh_.x5] - q[1] + sigma * half * ct7,
                            q[mesh_.y5] - q[2] + sigma * half * st7);
    const double l = d.norm();
    double fl = 0;
    const double f = spring_.force(l - (sp == 0 ? p.l10 : p.l20), &fl);
    Eigen::Matrix<double, 2, 5> D;
    D << 1, 0, -1, 0, -sigma * half * st7, 0, 1, 0, -1, sigma * half * ct7;
    const Eigen::Matrix<double, 5, 1> grad = D.transpose() * d / l;
    if (R)
      for (int a = 0; a < 5; ++a) (*R)[v[a]] += f * grad[a];
    if (!K) continue;
    Eigen::Matrix<double, 5, 5> H = D.transpose() * D;
    H(4, 4) += sigma * half * (-d.x() * ct7 - d.y() * st7);
    H = (H - grad * grad.transpose()) / l;
    const Eigen::Matrix<double, 5, 5> Ks = fl * grad * grad.transpose() + f * H;
    for (int a = 0; a < 5; ++a)
      for (int b = 0; b < 5; ++b) (*K)(v[a], v[b]) += Ks(a, b);
  }
}

template <class Matrix>
void FlexibleDsa380Pantograph::add_drive(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                         Eigen::VectorXd* R, Matrix* K, Matrix* C) const {
  const Dsa380Parameters& p = p_.rigid;
  if (R) (*R)[0] += p.kr * (q[0] - p.theta_r0) - M0_;  // drive spring, bellows torque
  if (K) (*K)(0, 0) += p.kr;
  if (damper_active(qd)) {  // f_d(v_a) h, v_a = h θ̇, h = dl_a/dθ (A.13–A.19)
    const Jet la = damper_length(p, q[0]);
    const double h = la[1], h1 = la[2], va = h * qd[0];
    const double fd = damper_.force(va), fd1 = damper_.dforce(va);
    if (R) (*R)[0] += fd * h;
    if (K) {
      (*C)(0, 0) += fd1 * h * h;
      (*K)(0, 0) += fd1 * h1 * qd[0] * h + fd * h1;
    }
  }
  if (e_.friction) {  // head–frame friction (2.16–2.17), v_r = ẏ10 − ẏ5
    const int y5 = mesh_.y5;
    const double vr = qd[2] - qd[y5];
    const double Ff = friction_.force(vr);
    if (R) {
      (*R)[2] += Ff;
      (*R)[y5] -= Ff;
    }
    if (K) {
      const double dFf = friction_.dforce(vr);  // (3.32)
      (*C)(2, 2) += dFf;
      (*C)(2, y5) -= dFf;
      (*C)(y5, 2) -= dFf;
      (*C)(y5, y5) += dFf;
    }
  }
}

template <class Matrix>
void FlexibleDsa380Pantograph::apply_restraints(const Eigen::VectorXd& qdd, Eigen::VectorXd* R,
                                                Matrix* K, Matrix* C, Matrix* M) const {
  const double m7 = p_.rigid.m[6], LG7 = p_.rigid.LG[6];
  int row = -1;
  if (e_.head_restraint == Dsa380Effects::HeadRestraint::rotation) row = 3;
  if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) row = 1;
  if (row < 0) return;
  if (K) {
    zero_row(*K, row);
    zero_row(*C, row);
  }
  if (M) zero_row(*M, row);
  if (row == 3) {  // θ̈7 = 0 (A.37)
    const double J = p_.rigid.I[6] + m7 * LG7 * LG7;
    if (R) (*R)[3] = J * qdd[3];
    if (M) (*M)(3, 3) = J;
  } else {  // ẍ10 = ẍ5 (A.38)
    if (R) (*R)[1] = m7 * (qdd[1] - qdd[mesh_.x5]);
    if (M) {
      (*M)(1, 1) = m7;
      (*M)(1, mesh_.x5) = -m7;
    }
  }
}

void FlexibleDsa380Pantograph::assemble(double ab, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                        Eigen::VectorXd* R, MatrixRef* K, MatrixRef* C,
                                        MatrixRef* M) const {
  if (R) R->noalias() = bar_mass_sparse_ * qdd + bar_weight_;
  if (R && ab != 0) *R += ab * bar_masses_;
  if (K) {
    K->setZero();
    C->setZero();
  }
  if (M) *M = bar_mass_;
  if (R || K) add_beams(q, R, K);
  add_head(ab, q, qd, qdd, R, K, C, M);
  if (R || K) add_drive(q, qd, R, K, C);
  if (R) bellows_.add_residual(p_.rigid, 0, bellows_dof(), q, qd, qdd, *R);
  if (K)
    bellows_.add_tangents(p_.rigid, 0, bellows_dof(), q, *K, *C, *M);
  else if (M)
    bellows_.add_mass(bellows_dof(), *M);
  apply_restraints(qdd, R, K, C, M);
}

void FlexibleDsa380Pantograph::residual(double t, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                        Eigen::Ref<Eigen::VectorXd> R) const {
  Eigen::VectorXd r(dof_count());
  assemble(frame_.acceleration(t), q, qd, qdd, &r, nullptr, nullptr, nullptr);
  R = r;
}

void FlexibleDsa380Pantograph::tangents(double t, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                        Eigen::Ref<Eigen::MatrixXd> dR_dq,
                                        Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                                        Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const {
  MatrixRef K(dR_dq), C(dR_dqd), M(dR_dqdd);
  assemble(frame_.acceleration(t), q, qd, qdd, nullptr, &K, &C, &M);
}

// As tangents() summed with the shifts: the beams' constant mass, then what
// assemble() adds to K, C and M, each entry as written there (no dense n x n).
bool FlexibleDsa380Pantograph::sparse_step_tangent(double t, const Eigen::VectorXd& q,
                                                   const Eigen::VectorXd& qd,
                                                   const Eigen::VectorXd& qdd, double shift_v,
                                                   double shift_a,
                                                   Eigen::SparseMatrix<double>& J) const {
  triplets_.clear();
  TripletView K(triplets_, 1.0), C(triplets_, shift_v), M(triplets_, shift_a);
  M.add(bar_mass_sparse_);
  add_beams(q, nullptr, &K);
  add_head(frame_.acceleration(t), q, qd, qdd, nullptr, &K, &C, &M);
  add_drive(q, qd, nullptr, &K, &C);
  bellows_.add_tangents(p_.rigid, 0, bellows_dof(), q, K, C, M);
  apply_restraints(qdd, nullptr, &K, &C, &M);
  tangent_pattern_.assemble(triplets_, dof_count(), J);
  return true;
}

// As mass(): the beams' constant mass and the head's, bellows' and
// restraints' entries.
bool FlexibleDsa380Pantograph::sparse_mass(double t, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& qd,
                                           Eigen::SparseMatrix<double>& M) const {
  const int n = dof_count();
  const Eigen::VectorXd qdd = Eigen::VectorXd::Zero(n);
  triplets_.clear();
  TripletView m(triplets_, 1.0);
  m.add(bar_mass_sparse_);
  add_head<TripletView>(frame_.acceleration(t), q, qd, qdd, nullptr, nullptr, nullptr, &m);
  bellows_.add_mass(bellows_dof(), m);
  apply_restraints<TripletView>(qdd, nullptr, nullptr, nullptr, &m);
  M.resize(n, n);
  M.setFromTriplets(triplets_.begin(), triplets_.end());
  return true;
}

void FlexibleDsa380Pantograph::mass(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                    Eigen::Ref<Eigen::MatrixXd> M) const {
  MatrixRef m(M);
  assemble(frame_.acceleration(t), q, qd, Eigen::VectorXd::Zero(dof_count()), nullptr, nullptr,
           nullptr, &m);
}

double FlexibleDsa380Pantograph::kinetic_energy(const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qd) const {
  const Dsa380Parameters& p = p_.rigid;
  const double m7 = p.m[6], LG7 = p.LG[6];
  const double s = std::sin(q[3] - p.thetaG[6]), c = std::cos(q[3] - p.thetaG[6]);
  return 0.5 * qd.dot(bar_mass_ * qd) + 0.5 * m7 * (qd[1] * qd[1] + qd[2] * qd[2]) +
         0.5 * (p.I[6] + m7 * LG7 * LG7) * qd[3] * qd[3] +
         m7 * LG7 * qd[3] * (c * qd[2] - s * qd[1]) +  // head as in (A.7)
         bellows_.kinetic_energy(bellows_dof(), qd);
}

double FlexibleDsa380Pantograph::potential_energy(const Eigen::VectorXd& q) const {
  const Dsa380Parameters& p = p_.rigid;
  double V = bar_weight_.dot(q) + 0.5 * p.kr * (q[0] - p.theta_r0) * (q[0] - p.theta_r0) +
             p.m[6] * p.g * (q[2] + p.LG[6] * std::sin(q[3] - p.thetaG[6]));
  for (const auto& e : mesh_.elements)
    V += planar_beam_evaluate(e.beam, gather(e, q), false).energy;
  const double half = 0.5 * p.L7, ct7 = std::cos(q[3]), st7 = std::sin(q[3]);
  for (int sp = 0; sp < 2; ++sp) {
    const double sigma = sp == 0 ? 1.0 : -1.0;
    const double l = std::hypot(q[mesh_.x5] - q[1] + sigma * half * ct7,
                                q[mesh_.y5] - q[2] + sigma * half * st7);
    const double e = l - (sp == 0 ? p.l10 : p.l20);
    V += spring_.energy(e);
  }
  return V + bellows_.potential_energy(bellows_dof(), q);
}

PowerSplit FlexibleDsa380Pantograph::power(double t, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& qd) const {
  PowerSplit P;
  P.external = M0_ * qd[0] + aero_force_ * qd[2];
  if (frame_.moves()) P.base = -frame_.acceleration(t) * base_inertia(q).dot(qd);
  bellows_.add_power(p_.rigid, 0, bellows_dof(), q, qd, &P);
  if (damper_active(qd)) {
    const double va = damper_length(p_.rigid, q[0])[1] * qd[0];
    P.dissipative += damper_.power(va);
  }
  if (e_.friction) {
    const double vr = qd[2] - qd[mesh_.y5];
    P.dissipative += friction_.power(vr);
  }
  return P;
}

}  // namespace pcsim::pantograph
