#include "pcsim/pantograph/calibration.hpp"

#include <cmath>

#include "pcsim/pantograph/linear.hpp"

namespace pcsim::pantograph {

std::vector<double> dsa380_frequencies(const Dsa380Parameters& p, double contact_force,
                                       double working_height, std::vector<int>* dominant) {
  Dsa380Pantograph model(p, Dsa380Effects{}, 0.0);
  const Eigen::VectorXd q0 = model.static_equilibrium(contact_force, working_height);
  const auto modes = undamped_modes_eigen(linearise(model, q0));
  std::vector<double> f;
  if (dominant) dominant->clear();
  for (const auto& m : modes) {
    f.push_back(m.frequency_hz);
    if (dominant) dominant->push_back(m.dominant_dof);
  }
  return f;
}

namespace {
void set_x(Dsa380Parameters* p, const Eigen::Vector4d& x) {
  p->kr = std::exp(x[0]);
  p->kl = std::exp(x[1]);
  p->l10 = p->l20 = std::exp(x[2]);
  p->I[6] = std::exp(x[3]);
}
Eigen::Vector4d residual_of(const Dsa380Parameters& p, const std::array<double, 4>& target,
                            double F0, double h0) {
  // Thesis order: head rotation < frame < head vertical < head horizontal. The frame mode
  // is the one with the largest share of θ; the other three are matched in ascending order.
  Dsa380Pantograph model(p, Dsa380Effects{}, 0.0);
  const Eigen::VectorXd q0 = model.static_equilibrium(F0, h0);
  const LinearModel lin = linearise(model, q0);
  const auto modes = undamped_modes_eigen(lin);
  if (modes.size() != 4) throw SolverError("calibration: the model has not 4 positive frequencies");
  int frame = 0;
  double best = -1;
  for (int k = 0; k < 4; ++k) {
    const double share = lin.M(0, 0) * std::norm(modes[k].shape[0]) /
                         (modes[k].shape.adjoint() * lin.M * modes[k].shape)(0, 0).real();
    if (share > best) best = share, frame = k;
  }
  Eigen::Vector4d r;
  r[1] = std::log(modes[frame].frequency_hz / target[1]);
  const int slot[3] = {0, 2, 3};
  for (int k = 0, s = 0; k < 4; ++k)
    if (k != frame) r[slot[s]] = std::log(modes[k].frequency_hz / target[slot[s]]), ++s;
  return r;
}
}  // namespace

CalibrationResult calibrate_dsa380(Dsa380Parameters p, const std::array<double, 4>& target,
                                   double F0, double h0) {
  Eigen::Vector4d x(std::log(p.kr), std::log(p.kl), std::log(p.l10), std::log(p.I[6]));
  CalibrationResult out;
  for (int it = 0; it < 60; ++it) {
    set_x(&p, x);
    const Eigen::Vector4d r = residual_of(p, target, F0, h0);
    out.iterations = it;
    if (r.cwiseAbs().maxCoeff() < 1e-10) break;
    Eigen::Matrix4d J;
    const double h = 1e-6;
    for (int j = 0; j < 4; ++j) {
      Eigen::Vector4d xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      Dsa380Parameters pp = p, pm = p;
      set_x(&pp, xp);
      set_x(&pm, xm);
      J.col(j) = (residual_of(pp, target, F0, h0) - residual_of(pm, target, F0, h0)) / (2 * h);
    }
    Eigen::Vector4d dx = J.fullPivLu().solve(-r);
    const double big = dx.cwiseAbs().maxCoeff();
    if (big > 0.3) dx *= 0.3 / big;
    x += dx;
  }
  set_x(&p, x);
  out.params = p;
  out.target_hz.assign(target.begin(), target.end());
  out.obtained_hz = dsa380_frequencies(p, F0, h0, &out.dominant_dof);
  return out;
}

}  // namespace pcsim::pantograph
