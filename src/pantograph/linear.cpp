#include "pcsim/pantograph/linear.hpp"

#include <algorithm>
#include <cmath>

#include "pcsim/core/error.hpp"

namespace pcsim::pantograph {

LinearModel linearise(const PantographModel& model, const Eigen::VectorXd& q0) {
  const int n = model.dof_count();
  LinearModel lin;
  lin.M.resize(n, n);
  lin.C.resize(n, n);
  lin.K.resize(n, n);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  model.tangents(0.0, q0, zero, zero, lin.K, lin.C, lin.M);
  lin.q0 = q0;
  lin.dof_names = model.dof_names();
  return lin;
}

LinearisedPantograph::LinearisedPantograph(LinearModel lin, int contact_dof, double contact_offset,
                                           double contact_force)
    : lin_(std::move(lin)), c_(contact_dof), offset_(contact_offset), F0_(contact_force) {}

void LinearisedPantograph::residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                    const Eigen::VectorXd& qdd,
                                    Eigen::Ref<Eigen::VectorXd> R) const {
  R.noalias() = lin_.M * qdd + lin_.C * qd + lin_.K * (q - lin_.q0);
  R[c_] -= F0_;
}

void LinearisedPantograph::tangents(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                    const Eigen::VectorXd&, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                                    Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                                    Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const {
  dR_dq = lin_.K;
  dR_dqd = lin_.C;
  dR_dqdd = lin_.M;
}

double LinearisedPantograph::kinetic_energy(const Eigen::VectorXd&,
                                            const Eigen::VectorXd& qd) const {
  return 0.5 * qd.dot(lin_.M * qd);
}

double LinearisedPantograph::potential_energy(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd d = q - lin_.q0;
  return 0.5 * d.dot(lin_.K * d);
}

PowerSplit LinearisedPantograph::power(double, const Eigen::VectorXd&,
                                       const Eigen::VectorXd& qd) const {
  return {-qd.dot(lin_.C * qd), F0_ * qd[c_]};
}

namespace {

constexpr double kTwoPi = 2 * M_PI;

void finish_shape(const LinearModel& lin, Mode* m) {
  const int n = static_cast<int>(lin.M.rows());
  Eigen::Index imax = 0;
  m->shape.cwiseAbs().maxCoeff(&imax);
  m->shape /= m->shape[imax];
  double best = -1;
  for (int i = 0; i < n; ++i) {
    const double share = std::abs(lin.M(i, i)) * std::norm(m->shape[i]);
    if (share > best) best = share, m->dominant_dof = i;
  }
}

}  // namespace

std::vector<int> restrained_rows(const LinearModel& lin) {
  std::vector<int> rows;
  for (int i = 0; i < lin.K.rows(); ++i)
    if ((lin.K.row(i).array() == 0.0).all() && (lin.C.row(i).array() == 0.0).all() &&
        (lin.M.row(i).array() != 0.0).any())
      rows.push_back(i);
  return rows;
}

RestraintReduction reduce_restraints(const LinearModel& lin) {
  const std::vector<int> rows = restrained_rows(lin);
  RestraintReduction r;
  if (rows.empty()) {
    r.reduced = lin;
    r.T = Eigen::MatrixXd::Identity(lin.M.rows(), lin.M.rows());
    return r;
  }
  const int n = static_cast<int>(lin.M.rows()), nr = static_cast<int>(rows.size());
  Eigen::MatrixXd MR(nr, n);
  std::vector<int> free_rows;
  for (int i = 0, k = 0; i < n; ++i)
    if (k < nr && rows[k] == i)
      MR.row(k++) = lin.M.row(i);
    else
      free_rows.push_back(i);
  // Kernel by full-pivot LU: each basis vector is a unit vector minus the pivots' share,
  // exact for the single-entry rows of A.37 and two-entry rows of A.38.
  r.T = Eigen::FullPivLU<Eigen::MatrixXd>(MR).kernel();
  if (r.T.cols() != n - nr) throw SolverError("modes: restrained rows are dependent");
  auto rows_of = [&](const Eigen::MatrixXd& A) {
    Eigen::MatrixXd out(free_rows.size(), n);
    for (std::size_t k = 0; k < free_rows.size(); ++k) out.row(k) = A.row(free_rows[k]);
    return Eigen::MatrixXd(out * r.T);
  };
  r.reduced.K = rows_of(lin.K);
  r.reduced.C = rows_of(lin.C);
  r.reduced.M = rows_of(lin.M);
  r.reduced.q0 = Eigen::VectorXd::Zero(n - nr);
  return r;
}

std::vector<Mode> undamped_modes_from_eigenpairs(const LinearModel& lin,
                                                 const Eigen::VectorXcd& lambda,
                                                 const Eigen::MatrixXcd& vec) {
  // λ = ω² of K φ = λ M φ.
  std::vector<Mode> modes;
  for (int k = 0; k < lambda.size(); ++k) {
    const double w2 = lambda[k].real();
    if (!std::isfinite(w2) || !(w2 > 0)) continue;  // unstable (or neutral) equilibrium
    Mode m;
    m.eigenvalue = {0.0, std::sqrt(w2)};
    m.frequency_hz = std::sqrt(w2) / kTwoPi;
    m.shape = vec.col(k);
    finish_shape(lin, &m);
    modes.push_back(m);
  }
  std::sort(modes.begin(), modes.end(),
            [](const Mode& a, const Mode& b) { return a.frequency_hz < b.frequency_hz; });
  return modes;
}

void state_space(const LinearModel& lin, Eigen::MatrixXd* A, Eigen::MatrixXd* B) {
  const int n = static_cast<int>(lin.M.rows());
  A->setZero(2 * n, 2 * n);
  B->setZero(2 * n, 2 * n);
  A->topLeftCorner(n, n) = lin.C;
  A->topRightCorner(n, n) = lin.M;
  A->bottomLeftCorner(n, n) = lin.M;
  B->topLeftCorner(n, n) = lin.K;
  B->bottomRightCorner(n, n) = -lin.M;
}

std::vector<Mode> damped_modes_from_eigenpairs(const LinearModel& lin,
                                               const Eigen::VectorXcd& lambda,
                                               const Eigen::MatrixXcd& vec) {
  const int n = static_cast<int>(lin.M.rows());
  std::vector<Mode> modes;
  for (int k = 0; k < lambda.size(); ++k) {
    const std::complex<double> l = lambda[k];
    const double tol = 1e-9 * std::max(1.0, std::abs(l));
    if (!std::isfinite(std::abs(l)) || l.imag() < -tol) continue;  // the conjugate
    Mode m;
    m.real_root = l.imag() <= tol;
    m.eigenvalue = m.real_root ? std::complex<double>(l.real(), 0.0) : l;
    const double w = std::abs(l);
    m.frequency_hz = w / kTwoPi;
    m.damping_ratio = -l.real() / w;  // (2.28)
    m.state_vector = vec.col(k);
    if (m.real_root) m.state_vector = m.state_vector.real().cast<std::complex<double>>();
    m.shape = m.state_vector.head(n);
    finish_shape(lin, &m);
    modes.push_back(m);
  }
  std::sort(modes.begin(), modes.end(),
            [](const Mode& a, const Mode& b) { return a.frequency_hz < b.frequency_hz; });
  return modes;
}

std::vector<Mode> undamped_modes_eigen(const LinearModel& lin) {
  const RestraintReduction r = reduce_restraints(lin);
  Eigen::EigenSolver<Eigen::MatrixXd> es(r.reduced.M.lu().solve(r.reduced.K));
  const Eigen::MatrixXcd vectors = r.T * es.eigenvectors();
  return undamped_modes_from_eigenpairs(lin, es.eigenvalues(), vectors);
}

std::vector<Mode> damped_modes_eigen(const LinearModel& lin) {
  const RestraintReduction r = reduce_restraints(lin);
  Eigen::MatrixXd A, B;
  state_space(r.reduced, &A, &B);
  Eigen::EigenSolver<Eigen::MatrixXd> es(A.lu().solve(-B));
  return damped_modes_from_eigenpairs(lin, es.eigenvalues(), expand_state(r.T, es.eigenvectors()));
}

Eigen::MatrixXcd expand_state(const Eigen::MatrixXd& T, const Eigen::MatrixXcd& Y) {
  const Eigen::Index m = T.cols();
  Eigen::MatrixXcd out(2 * T.rows(), Y.cols());
  out.topRows(T.rows()) = T * Y.topRows(m);
  out.bottomRows(T.rows()) = T * Y.bottomRows(m);
  return out;
}

Eigen::MatrixXcd dynamic_stiffness(const LinearModel& lin, double omega) {
  const std::complex<double> I(0, 1);
  return lin.K.cast<std::complex<double>>() + I * omega * lin.C.cast<std::complex<double>>() -
         omega * omega * lin.M.cast<std::complex<double>>();
}

std::complex<double> frf_direct(const LinearModel& lin, int i, int j, double omega) {
  const Eigen::MatrixXcd D = dynamic_stiffness(lin, omega);
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(lin.M.rows());
  f[j] = 1.0;
  return D.fullPivLu().solve(f)[i];
}

std::complex<double> transmissibility_direct(const LinearModel& lin, const BaseSupport& base, int i,
                                             double omega) {
  if (base.dof < 0) throw SolverError("transmissibility: the model has no base support");
  const std::complex<double> load(base.stiffness, omega * base.damping);
  return frf_direct(lin, i, base.dof, omega) * load;
}

std::complex<double> transmissibility_frame(const LinearModel& lin, const Eigen::VectorXd& inertia,
                                            int i, double omega) {
  const Eigen::MatrixXcd D = dynamic_stiffness(lin, omega);
  const Eigen::VectorXcd f = omega * omega * inertia.cast<std::complex<double>>();
  return 1.0 + D.fullPivLu().solve(f)[i];
}

std::vector<std::complex<double>> frf_modal(const LinearModel& lin, const std::vector<Mode>& damped,
                                            int i, int j, const std::vector<double>& omegas) {
  if (!lin.M.isApprox(lin.M.transpose()) || !lin.K.isApprox(lin.K.transpose()) ||
      !lin.C.isApprox(lin.C.transpose()))
    throw SolverError("frf_modal: needs symmetric M, C, K (use frf_direct with restraints)");
  Eigen::MatrixXd A, B;
  state_space(lin, &A, &B);
  const Eigen::MatrixXcd Ac = A.cast<std::complex<double>>();
  std::vector<std::complex<double>> numerator;  // φ_i φ_j / a_r
  for (const auto& m : damped) {
    const Eigen::VectorXcd& phi = m.state_vector;
    const std::complex<double> a = phi.transpose() * Ac * phi;
    numerator.push_back(phi[i] * phi[j] / a);
  }
  const std::complex<double> I(0, 1);
  std::vector<std::complex<double>> h(omegas.size(), 0.0);
  for (std::size_t k = 0; k < omegas.size(); ++k)
    for (std::size_t r = 0; r < damped.size(); ++r) {
      const std::complex<double> s = I * omegas[k], lambda = damped[r].eigenvalue;
      h[k] += numerator[r] / (s - lambda);
      // Conjugate pair: φ̄, λ̄.
      if (!damped[r].real_root) h[k] += std::conj(numerator[r]) / (s - std::conj(lambda));
    }
  return h;
}

std::complex<double> frf_modal(const LinearModel& lin, const std::vector<Mode>& damped, int i,
                               int j, double omega) {
  return frf_modal(lin, damped, i, j, std::vector<double>{omega})[0];
}

}  // namespace pcsim::pantograph
