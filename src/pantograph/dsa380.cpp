#include "pcsim/pantograph/dsa380.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcsim::pantograph {
namespace {

// Third point of a triangle: from point A, bar of length La at angle α to the joint J,
// with |B − J| = Lb; 'branch' picks one of the two assemblies. Returns the angle of A→J.
Jet triangle_angle(const Jet& ax, const Jet& ay, const Jet& bx, const Jet& by, double La, double Lb,
                   int branch, bool* ok) {
  const Jet dx = bx - ax, dy = by - ay;
  const Jet d2 = dx * dx + dy * dy;
  const Jet d = sqrt(d2);
  const Jet cos_alpha = (d2 + Jet(La * La - Lb * Lb)) / (Jet(2 * La) * d);
  if (!(std::abs(cos_alpha[0]) < 1.0)) {
    *ok = false;
    return atan2(dy, dx);
  }
  const Jet alpha = acos(cos_alpha);
  return branch > 0 ? atan2(dy, dx) + alpha : atan2(dy, dx) - alpha;
}

}  // namespace

const char* dsa380_mode_label(int dof) {
  static const char* labels[4] = {"frame", "head horizontal", "head vertical", "head rotation"};
  return dof >= 0 && dof < 4 ? labels[dof] : "";
}

Dsa380Kinematics dsa380_kinematics(const Dsa380Parameters& p, double theta_value) {
  Dsa380Kinematics k;
  const Jet th = Jet::variable(theta_value);
  const Jet c1 = cos(th), s1 = sin(th);
  // Lower loop fixed–1–2–3 (A.1, A.2): P4 = P1 + L1 e(θ); P3 = L2 e(θ2), |P4 − P3| = L3.
  k.x4 = Jet(p.x1) + Jet(p.L1) * c1;
  k.y4 = Jet(p.y1) + Jet(p.L1) * s1;
  k.theta2 =
      triangle_angle(Jet(0.0), Jet(0.0), k.x4, k.y4, p.L2, p.L3, p.lower_branch, &k.assembled);
  k.x3 = Jet(p.L2) * cos(k.theta2);
  k.y3 = Jet(p.L2) * sin(k.theta2);
  k.theta3 = atan2(k.y4 - k.y3, k.x4 - k.x3);
  k.theta4 = k.theta3 + Jet(p.theta34 - M_PI);
  k.x5 = k.x4 + Jet(p.L4) * cos(k.theta4);
  k.y5 = k.y4 + Jet(p.L4) * sin(k.theta4);
  // Upper loop 1–4–5–6 (A.1, A.3): P6 = P1 + r e(θ + θr); P6 → J (bar 5) → P5 (bar 6).
  const Jet thr = th + Jet(p.theta_r);
  k.x6 = Jet(p.x1) + Jet(p.r) * cos(thr);
  k.y6 = Jet(p.y1) + Jet(p.r) * sin(thr);
  k.theta5 = triangle_angle(k.x6, k.y6, k.x5, k.y5, p.L5, p.L6, p.upper_branch, &k.assembled);
  k.xj = k.x6 + Jet(p.L5) * cos(k.theta5);
  k.yj = k.y6 + Jet(p.L5) * sin(k.theta5);
  k.theta6 = atan2(k.y5 - k.yj, k.x5 - k.xj);
  // Damper between fixed point 13 and point 1p (A.14).
  const Jet th1p = th + Jet(p.theta_1p);
  const Jet dxa = Jet(p.x1 - p.x13) + Jet(p.L1p) * cos(th1p);
  const Jet dya = Jet(p.y1 - p.y13) + Jet(p.L1p) * sin(th1p);
  k.damper_length = sqrt(dxa * dxa + dya * dya);
  // Centres of gravity (A.6, A.10): first point of the bar + LGi e(θi − θGi).
  const std::array<Jet, 6> angle = {th, k.theta2, k.theta3, k.theta4, k.theta5, k.theta6};
  const std::array<Jet, 6> start_x = {Jet(p.x1), Jet(0.0), k.x3, k.x4, k.x6, k.xj};
  const std::array<Jet, 6> start_y = {Jet(p.y1), Jet(0.0), k.y3, k.y4, k.y6, k.yj};
  Jet inertia, gravity;
  for (int i = 0; i < 6; ++i) {
    const Jet a = angle[i] - Jet(p.thetaG[i]);
    k.xg[i] = start_x[i] + Jet(p.LG[i]) * cos(a);
    k.yg[i] = start_y[i] + Jet(p.LG[i]) * sin(a);
    const Jet vx = k.xg[i].derivative(), vy = k.yg[i].derivative();
    const Jet w = angle[i].derivative();
    inertia += Jet(p.m[i]) * (vx * vx + vy * vy) + Jet(p.I[i]) * (w * w);  // (A.7)
    gravity += Jet(p.g * p.m[i]) * k.yg[i];
  }
  k.inertia = inertia;
  k.gravity_energy = gravity;
  return k;
}

Dsa380Pantograph::Dsa380Pantograph(Dsa380Parameters params, Dsa380Effects effects, double speed_m_s)
    : p_(std::move(params)), e_(effects) {
  if (e_.aerodynamic)
    aero_force_ = p_.aero_a + p_.aero_b * speed_m_s + p_.aero_c * speed_m_s * speed_m_s;
  bellows_ = Bellows(p_.bellows, e_.uplift_characteristic, aero_force_);
  spring_ = head_spring(p_);
  damper_ = frame_damper(p_, e_);
  friction_ = head_friction(e_);
}

std::vector<std::string> Dsa380Pantograph::dof_names() const {
  std::vector<std::string> names = {"theta", "x10", "y10", "theta7"};
  if (bellows_.has_state()) names.push_back("bellows_dM");
  return names;
}

void Dsa380Pantograph::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const {
  const auto k = dsa380_kinematics(p_, q[0]);
  const double th = q[0], x10 = q[1], y10 = q[2], th7 = q[3];
  const double thd = qd[0], yd = qd[2], th7d = qd[3];
  const double m7 = p_.m[6], LG7 = p_.LG[6], I7 = p_.I[6];
  const double s = std::sin(th7 - p_.thetaG[6]), c = std::cos(th7 - p_.thetaG[6]);
  const double a = k.inertia[0], a1 = k.inertia[1];
  R[0] = a * qdd[0] + 0.5 * a1 * thd * thd + p_.kr * (th - p_.theta_r0) + k.gravity_energy[1] - M0_;
  R[1] = m7 * qdd[1] - m7 * LG7 * (s * qdd[3] + c * th7d * th7d);
  R[2] = m7 * qdd[2] + m7 * LG7 * (c * qdd[3] - s * th7d * th7d) + m7 * p_.g - aero_force_;
  R[3] =
      m7 * LG7 * (c * qdd[2] - s * qdd[1]) + (I7 + m7 * LG7 * LG7) * qdd[3] + m7 * p_.g * LG7 * c;
  // Head springs (A.11, A.32–A.34).
  const double half = 0.5 * p_.L7, ct7 = std::cos(th7), st7 = std::sin(th7);
  for (int sp = 0; sp < 2; ++sp) {
    const double sigma = sp == 0 ? 1.0 : -1.0;
    const double dx = k.x5[0] - x10 + sigma * half * ct7;
    const double dy = k.y5[0] - y10 + sigma * half * st7;
    const double l = std::hypot(dx, dy);
    const double f = spring_.force(l - (sp == 0 ? p_.l10 : p_.l20)) / l;
    R[0] += f * (dx * k.x5[1] + dy * k.y5[1]);
    R[1] -= f * dx;
    R[2] -= f * dy;
    R[3] += f * sigma * half * (-dx * st7 + dy * ct7);
  }
  if (e_.damper) {  // damper through its lever (A.13–A.19)
    const double h = k.damper_length[1], va = h * thd;
    if (damper_.acts(k.y5[1] * thd)) R[0] += damper_.force(va) * h;
  }
  if (e_.friction) {  // smoothed Coulomb friction head–frame (2.16–2.17)
    const double vr = yd - k.y5[1] * thd;
    const double Ff = friction_.force(vr);
    R[0] -= Ff * k.y5[1];
    R[2] += Ff;
  }
  bellows_.add_residual(p_, 0, bellows_dof(), q, qd, qdd, R, &k);  // torque beyond M0
  add_base_residual(t, k, q, R);                                   // moving frame (dsa380_base.cpp)
  if (e_.head_restraint == Dsa380Effects::HeadRestraint::rotation) {
    R[3] = (I7 + m7 * LG7 * LG7) * qdd[3];  // θ̈7 = 0 (A.37)
  } else if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) {
    R[1] = m7 * (qdd[1] - k.x5[1] * qdd[0] - k.x5[2] * thd * thd);  // ẍ10 = ẍ5 (A.38)
  }
}

void Dsa380Pantograph::tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> Kq,
                                Eigen::Ref<Eigen::MatrixXd> Cq,
                                Eigen::Ref<Eigen::MatrixXd> Mq) const {
  const auto k = dsa380_kinematics(p_, q[0]);
  const double x10 = q[1], y10 = q[2], th7 = q[3];
  const double thd = qd[0], yd = qd[2], th7d = qd[3];
  const double m7 = p_.m[6], LG7 = p_.LG[6], I7 = p_.I[6];
  const double s = std::sin(th7 - p_.thetaG[6]), c = std::cos(th7 - p_.thetaG[6]);
  const double a = k.inertia[0], a1 = k.inertia[1], a2 = k.inertia[2];
  Kq.setZero();
  Cq.setZero();
  Mq.setZero();
  // Inertia and Coriolis (3.27–3.30).
  Mq(0, 0) = a;
  Kq(0, 0) = a1 * qdd[0] + 0.5 * a2 * thd * thd + p_.kr + k.gravity_energy[2];
  Cq(0, 0) = a1 * thd;
  Mq(1, 1) = m7;
  Mq(1, 3) = -m7 * LG7 * s;
  Kq(1, 3) = -m7 * LG7 * (c * qdd[3] - s * th7d * th7d);
  Cq(1, 3) = -2 * m7 * LG7 * c * th7d;
  Mq(2, 2) = m7;
  Mq(2, 3) = m7 * LG7 * c;
  Kq(2, 3) = m7 * LG7 * (-s * qdd[3] - c * th7d * th7d);
  Cq(2, 3) = -2 * m7 * LG7 * s * th7d;
  Mq(3, 1) = -m7 * LG7 * s;
  Mq(3, 2) = m7 * LG7 * c;
  Mq(3, 3) = I7 + m7 * LG7 * LG7;
  Kq(3, 3) = m7 * LG7 * (-s * qdd[2] - c * qdd[1]) - m7 * p_.g * LG7 * s;
  // Head springs (3.34): f ∇l, Hessian f' ∇l∇lᵀ + f (DᵀD + Σ d_k ∂²d_k)/l − f ∇l∇lᵀ/l.
  const double half = 0.5 * p_.L7, ct7 = std::cos(th7), st7 = std::sin(th7);
  for (int sp = 0; sp < 2; ++sp) {
    const double sigma = sp == 0 ? 1.0 : -1.0;
    const double dx = k.x5[0] - x10 + sigma * half * ct7;
    const double dy = k.y5[0] - y10 + sigma * half * st7;
    const double l = std::hypot(dx, dy);
    double fl = 0;
    const double f = spring_.force(l - (sp == 0 ? p_.l10 : p_.l20), &fl);
    Eigen::Matrix<double, 2, 4> D;
    D << k.x5[1], -1, 0, -sigma * half * st7, k.y5[1], 0, -1, sigma * half * ct7;
    const Eigen::Vector2d dvec(dx, dy);
    const Eigen::Vector4d grad = D.transpose() * dvec / l;
    Eigen::Matrix4d H = D.transpose() * D;
    H(0, 0) += dx * k.x5[2] + dy * k.y5[2];
    H(3, 3) += sigma * half * (-dx * ct7 - dy * st7);
    H = (H - grad * grad.transpose()) / l;
    Kq.topLeftCorner<4, 4>() += fl * grad * grad.transpose() + f * H;
  }
  if (e_.damper) {
    const double h = k.damper_length[1], h1 = k.damper_length[2], va = h * thd;
    if (damper_.acts(k.y5[1] * thd)) {
      const double fd = damper_.force(va), fd1 = damper_.dforce(va);
      Cq(0, 0) += fd1 * h * h;
      Kq(0, 0) += fd1 * h1 * thd * h + fd * h1;
    }
  }
  if (e_.friction) {
    const double vr = yd - k.y5[1] * thd;
    const double Ff = friction_.force(vr), dFf = friction_.dforce(vr);  // (3.32)
    const Eigen::Vector4d gv(-k.y5[1], 0, 1, 0);
    Cq.topLeftCorner<4, 4>() += dFf * gv * gv.transpose();
    Kq.col(0).head<4>() += dFf * (-k.y5[2] * thd) * gv;
    Kq(0, 0) += -Ff * k.y5[2];
  }
  bellows_.add_tangents(p_, 0, bellows_dof(), q, Kq, Cq, Mq, &k);
  add_base_tangent(t, k, q, Kq);
  if (e_.head_restraint == Dsa380Effects::HeadRestraint::rotation) {
    Kq.row(3).setZero();
    Cq.row(3).setZero();
    Mq.row(3).setZero();
    Mq(3, 3) = I7 + m7 * LG7 * LG7;
  } else if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) {
    Kq.row(1).setZero();
    Cq.row(1).setZero();
    Mq.row(1).setZero();
    Kq(1, 0) = m7 * (-k.x5[2] * qdd[0] - k.x5[3] * thd * thd);
    Cq(1, 0) = -2 * m7 * k.x5[2] * thd;
    Mq(1, 0) = -m7 * k.x5[1];
    Mq(1, 1) = m7;
  }
}

double Dsa380Pantograph::kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  const auto k = dsa380_kinematics(p_, q[0]);
  const double m7 = p_.m[6], LG7 = p_.LG[6];
  const double s = std::sin(q[3] - p_.thetaG[6]), c = std::cos(q[3] - p_.thetaG[6]);
  return 0.5 * k.inertia[0] * qd[0] * qd[0] + 0.5 * m7 * (qd[1] * qd[1] + qd[2] * qd[2]) +
         0.5 * (p_.I[6] + m7 * LG7 * LG7) * qd[3] * qd[3] +
         m7 * LG7 * qd[3] * (c * qd[2] - s * qd[1]) +  // (A.7)
         bellows_.kinetic_energy(bellows_dof(), qd);
}

double Dsa380Pantograph::potential_energy(const Eigen::VectorXd& q) const {
  const auto k = dsa380_kinematics(p_, q[0]);
  const double m7 = p_.m[6];
  double V = 0.5 * p_.kr * (q[0] - p_.theta_r0) * (q[0] - p_.theta_r0) + k.gravity_energy[0] +
             m7 * p_.g * (q[2] + p_.LG[6] * std::sin(q[3] - p_.thetaG[6]));  // (A.10)
  const double half = 0.5 * p_.L7, ct7 = std::cos(q[3]), st7 = std::sin(q[3]);
  for (int sp = 0; sp < 2; ++sp) {
    const double sigma = sp == 0 ? 1.0 : -1.0;
    const double l =
        std::hypot(k.x5[0] - q[1] + sigma * half * ct7, k.y5[0] - q[2] + sigma * half * st7);
    const double e = l - (sp == 0 ? p_.l10 : p_.l20);
    V += spring_.energy(e);
  }
  return V + bellows_.potential_energy(bellows_dof(), q);
}

PowerSplit Dsa380Pantograph::power(double t, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& qd) const {
  PowerSplit P;
  P.external = M0_ * qd[0] + aero_force_ * qd[2];
  if (frame_.moves()) P.base = -frame_.acceleration(t) * base_inertia(q).dot(qd);
  bellows_.add_power(p_, 0, bellows_dof(), q, qd, &P);
  if (!e_.damper && !e_.friction) return P;
  const auto k = dsa380_kinematics(p_, q[0]);
  if (e_.damper) {
    const double va = k.damper_length[1] * qd[0];
    if (damper_.acts(k.y5[1] * qd[0])) P.dissipative += damper_.power(va);
  }
  if (e_.friction) {
    const double vr = qd[2] - k.y5[1] * qd[0];
    P.dissipative += friction_.power(vr);
  }
  return P;
}

double dsa380_head_descent(const Dsa380Parameters& p, double load, double* dz_dload) {
  // (2.12): 2 f(l) z / l = W, l = sqrt(z² + (L7/2)²).
  const double half = 0.5 * p.L7, l0 = 0.5 * (p.l10 + p.l20);
  auto phi = [&](double z, double* dphi) {
    const double l = std::hypot(z, half), e = l - l0;
    double fl = 0;
    const double f = head_spring(p).force(e, &fl);
    *dphi = 2 * (fl * z * z / (l * l) + f * (1 / l - z * z / (l * l * l)));
    return 2 * f * z / l - load;
  };
  // Safeguarded Newton on [0, z_hi].
  double lo = 0, hi = 2 * l0 + 1.0, z = std::sqrt(std::max(l0 * l0 - half * half, 0.0)) + 1e-3;
  for (int it = 0; it < 200; ++it) {
    double dphi = 0;
    const double r = phi(z, &dphi);
    if (std::abs(r) < 1e-12 * std::max(1.0, std::abs(load))) {
      if (dz_dload) *dz_dload = 1 / dphi;
      return z;
    }
    if (r > 0)
      hi = z;
    else
      lo = z;
    double zn = dphi > 0 ? z - r / dphi : 0.5 * (lo + hi);
    if (!(zn > lo && zn < hi)) zn = 0.5 * (lo + hi);
    z = zn;
  }
  throw SolverError("dsa380: head equilibrium (2.12) did not converge");
}

double Dsa380Pantograph::head_descent(double contact_force) const {
  return dsa380_head_descent(p_, p_.m[6] * p_.g + contact_force - aero_force_, nullptr);
}

double Dsa380Pantograph::bellows_torque_formula(const Eigen::VectorXd& q0,
                                                double contact_force) const {
  // (2.14): M0 = dV/dθ + (m7 g + F0 − F_aero) dy5/dθ, V of the body (bars 1–6, spring kr).
  const auto k = dsa380_kinematics(p_, q0[0]);
  return p_.kr * (q0[0] - p_.theta_r0) + k.gravity_energy[1] +
         (p_.m[6] * p_.g + contact_force - aero_force_) * k.y5[1];
}

// Why no frame angle gives the working height h0 (InputError on key
// 'working_height'; the reader adds the file): the angle Newton reached and
// the heights the mechanism can reach under this contact force.
void Dsa380Pantograph::fail_working_height(double theta, double h0, double z,
                                           const std::string& what) const {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (double th = -M_PI; th <= M_PI; th += 1e-3) {
    const auto k = dsa380_kinematics(p_, th);
    if (!k.assembled) continue;
    lo = std::min(lo, k.y5[0] - z + p_.L7p);
    hi = std::max(hi, k.y5[0] - z + p_.L7p);
  }
  char text[400];
  std::snprintf(text, sizeof text,
                "DSA-380: %s at frame angle θ = %.4g rad (%.1f°) while solving (2.13) for working "
                "height %.4g m; under this contact force the mechanism reaches working heights "
                "from %.4g to %.4g m",
                what.c_str(), theta, theta * 180 / M_PI, h0, lo, hi);
  throw InputError("", "working_height", text);
}

Eigen::VectorXd Dsa380Pantograph::equilibrium_at_rest(double contact_force, double working_height) {
  bellows_.clear_reference();  // the fixed-torque equilibrium first: M0 at h0
  const double z = head_descent(contact_force);
  const double y10 = working_height - p_.L7p;
  const double h5 = y10 + z;
  // (2.13): y5(θ) = h5 by Newton.
  double th = p_.theta_guess;
  bool converged = false;
  for (int it = 0; it < 100; ++it) {
    const auto k = dsa380_kinematics(p_, th);
    if (!k.assembled)
      fail_working_height(th, working_height, z, "the mechanism cannot be assembled");
    const double r = k.y5[0] - h5;
    if (std::abs(r) < 1e-13) {
      converged = true;
      break;
    }
    double step = -r / k.y5[1];
    if (std::abs(step) > 0.2) step = step > 0 ? 0.2 : -0.2;
    th += step;
  }
  if (!converged) fail_working_height(th, working_height, z, "no frame angle reaches the height");
  const auto k = dsa380_kinematics(p_, th);
  const int n = dof_count();
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
  q0.head<4>() << th, k.x5[0], y10, 0.0;
  // Bellows torque: the θ-row of R without M0 (equivalent to 2.14 for a symmetric head).
  M0_ = 0;
  Eigen::VectorXd R(n);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  residual(0, q0, zero, zero, R);
  M0_ = R[0];
  residual(0, q0, zero, zero, R);
  R[2] += contact_force;
  if (R.norm() > 1e-8 * (1 + std::abs(contact_force)))  // asymmetric head: finish by Newton
    q0 = solve_static(contact_force, q0);
  bellows_.set_reference(p_, q0[0], contact_force, working_height);
  return q0;
}

Eigen::VectorXd Dsa380Pantograph::solve_static(double contact_force, Eigen::VectorXd q) const {
  const int n = dof_count();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd R(n);
  Eigen::MatrixXd Kq(n, n), Cq(n, n), Mq(n, n);
  const double scale = 1 + std::abs(contact_force) + p_.m[6] * p_.g;
  for (int it = 0; it < 60; ++it) {
    residual(0, q, zero, zero, R);
    tangents(0, q, zero, zero, Kq, Cq, Mq);
    R[2] += contact_force;
    if (e_.head_restraint == Dsa380Effects::HeadRestraint::rotation) {
      R[3] = q[3];
      Kq.row(3).setZero();
      Kq(3, 3) = 1;
    } else if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) {
      const auto k = dsa380_kinematics(p_, q[0]);
      R[1] = q[1] - k.x5[0];
      Kq.row(1).setZero();
      Kq(1, 0) = -k.x5[1];
      Kq(1, 1) = 1;
    }
    if (R.norm() < 1e-11 * scale) return q;
    Eigen::VectorXd dq = Kq.fullPivLu().solve(-R);
    const double big = dq.cwiseAbs().maxCoeff();
    if (big > 0.1) dq *= 0.1 / big;
    q += dq;
  }
  throw SolverError("dsa380: static Newton did not converge");
}

}  // namespace pcsim::pantograph
