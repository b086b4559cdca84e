#include "pcsim/simulation/pantograph_study.hpp"

#include <algorithm>
#include <cmath>

#include "pcsim/solvers/pantograph_modes.hpp"
#include "pcsim/solvers/pantograph_time.hpp"

namespace pcsim::simulation {

namespace {

using namespace pcsim::pantograph;

TimeStudyResult run_time(const StudyScene& s, const TimeStudy& st, const Eigen::VectorXd& q0) {
  TimeStudyResult r;
  TimeOptions opt = st.options;
  const Eigen::VectorXd v0 = Eigen::VectorXd::Zero(s.model->dof_count());
  for (const auto& sch : st.schemes) {
    opt.scheme = sch;
    TimeRun run;
    run.scheme = sch;
    run.history = solvers::integrate_pantograph(*s.model, q0, v0, st.force, opt);
    if (st.linear) {
      LinearisedPantograph lin(linearise(*s.model, q0), s.model->contact_dof(),
                               s.model->contact_offset(), s.contact_force);
      run.linear = solvers::integrate_pantograph(lin, q0, v0, st.force, opt);
      run.has_linear = true;
    }
    r.runs.push_back(std::move(run));
  }
  return r;
}

// Modes up to f_max_hz (all if 0).
std::vector<Mode> up_to(std::vector<Mode> modes, double f_max_hz) {
  if (f_max_hz > 0)
    modes.erase(std::remove_if(modes.begin(), modes.end(),
                               [&](const Mode& m) { return m.frequency_hz > f_max_hz; }),
                modes.end());
  return modes;
}

ModesStudyResult run_modes(const StudyScene& s, const ModesStudy& st, const Eigen::VectorXd& q0) {
  ModesStudyResult r;
  r.linear = linearise(*s.model, q0);
  r.undamped = up_to(solvers::undamped_modes_slepc(r.linear), st.f_max_hz);
  r.damped = up_to(solvers::damped_modes_slepc(r.linear), st.f_max_hz);
  const auto und_e = undamped_modes_eigen(r.linear), dam_e = damped_modes_eigen(r.linear);
  double diff = 0;
  for (size_t k = 0; k < r.undamped.size() && k < und_e.size(); ++k)
    diff = std::max(diff, std::abs(r.undamped[k].frequency_hz - und_e[k].frequency_hz) /
                              r.undamped[k].frequency_hz);
  for (size_t k = 0; k < r.damped.size() && k < dam_e.size(); ++k)
    if (!r.damped[k].real_root)
      diff = std::max(diff, std::abs(r.damped[k].frequency_hz - dam_e[k].frequency_hz) /
                                r.damped[k].frequency_hz);
  r.slepc_vs_eigen_max_relative_difference = diff;
  return r;
}

FrfStudyResult run_frf(const StudyScene& s, const FrfStudy& st, const Eigen::VectorXd& q0) {
  FrfStudyResult r;
  r.frequencies_hz = st.frequencies_hz;
  const LinearModel lin = linearise(*s.model, q0);
  const int c = r.dof = s.model->contact_dof();
  r.symmetric = lin.M.isApprox(lin.M.transpose()) && lin.K.isApprox(lin.K.transpose());
  std::vector<double> omegas;
  for (double f : st.frequencies_hz) omegas.push_back(2 * M_PI * f);
  for (double w : omegas) r.direct.push_back(frf_direct(lin, c, c, w));  // H_cc (2.36)
  const BaseSupport base = s.model->base_support();
  if (base.dof >= 0)
    for (double w : omegas) r.transmissibility.push_back(transmissibility_direct(lin, base, c, w));
  if (s.model->moving_frame()) {
    const Eigen::VectorXd b = s.model->base_inertia(q0);
    for (double w : omegas) r.transmissibility.push_back(transmissibility_frame(lin, b, c, w));
  }
  if (r.symmetric) {
    r.modal = frf_modal(lin, solvers::damped_modes_slepc(lin), c, c, omegas);  // (2.40)
    for (std::size_t k = 0; k < omegas.size(); ++k)
      r.direct_vs_modal_max_relative_difference =
          std::max(r.direct_vs_modal_max_relative_difference,
                   std::abs(r.direct[k] - r.modal[k]) / std::abs(r.direct[k]));
  }
  return r;
}

// Linear steady state under −A sin(ωt) e_c about q0: Δq(t) = Im(X e^{iωt}),
// X = [K + iωC − ω²M]⁻¹ (−A e_c); a run started there has (almost) no free vibration of
// the lightly damped head modes.
void linear_steady_state(const LinearModel& lin, int c, double A, double w, Eigen::VectorXd* q,
                         Eigen::VectorXd* v) {
  const std::complex<double> I(0, 1);
  const Eigen::MatrixXcd D = lin.K.cast<std::complex<double>>() +
                             I * w * lin.C.cast<std::complex<double>>() -
                             w * w * lin.M.cast<std::complex<double>>();
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(lin.q0.size());
  f[c] = -A;
  const Eigen::VectorXcd X = D.fullPivLu().solve(f);
  *q += X.imag();
  *v = w * X.real();
}

// Peak-to-peak / 2A of q[c] over the measurement window; NaN if the run diverged
// (e.g. the head overturning without restraint).
double sweep_point(const PantographModel& m, const LinearModel& lin, const SweepStudy& st,
                   double F0, double A, double f) {
  const int c = m.contact_dof();
  const double period = 1.0 / f, w = 2 * M_PI * f;
  const double t_meas0 = std::max(st.settle_s, st.settle_periods * period);
  TimeOptions opt;
  opt.scheme = st.scheme;
  opt.hht_alpha = st.hht_alpha;
  opt.dt = st.dt;
  opt.t_end = t_meas0 + st.measure_periods * period;
  try {
    Eigen::VectorXd qs = lin.q0, vs = Eigen::VectorXd::Zero(lin.q0.size());
    if (st.start_on_linear_steady_state) linear_steady_state(lin, c, A, w, &qs, &vs);
    const auto h = solvers::integrate_pantograph(
        m, qs, vs, [=](double t) { return F0 + A * std::sin(w * t); }, opt);
    double lo = 1e300, hi = -1e300;
    for (size_t k = 0; k < h.t.size(); ++k)
      if (h.t[k] >= t_meas0) lo = std::min(lo, h.q[k][c]), hi = std::max(hi, h.q[k][c]);
    return (hi - lo) / (2 * A);
  } catch (const SolverError&) {
    return std::nan("");
  }
}

SweepStudyResult run_sweep(const StudyScene& s, const SweepStudy& st, const Eigen::VectorXd& q0) {
  SweepStudyResult r;
  r.frequencies_hz = st.frequencies_hz;
  r.amplitudes = st.amplitudes;
  const LinearModel lin = linearise(*s.model, q0);
  std::unique_ptr<PantographModel> lin_model;
  if (st.linear)
    lin_model = std::make_unique<LinearisedPantograph>(lin, s.model->contact_dof(),
                                                       s.model->contact_offset(), s.contact_force);
  for (int pass = 0; pass < (lin_model ? 2 : 1); ++pass) {
    const PantographModel& m = pass == 0 ? *s.model : *lin_model;
    for (double A : st.amplitudes) {
      SweepCurve curve{pass == 0 ? "nonlinear" : "linear", A, {}};
      for (double f : st.frequencies_hz)
        curve.response.push_back(sweep_point(m, lin, st, s.contact_force, A, f));
      r.curves.push_back(std::move(curve));
    }
  }
  return r;
}

}  // namespace

StudyResult run_pantograph_study(StudyScene& s) {
  StudyResult r;
  r.q0 = s.model->static_equilibrium(s.contact_force, s.working_height);
  if (const auto* st = std::get_if<TimeStudy>(&s.study)) r.values = run_time(s, *st, r.q0);
  if (const auto* st = std::get_if<ModesStudy>(&s.study)) r.values = run_modes(s, *st, r.q0);
  if (const auto* st = std::get_if<FrfStudy>(&s.study)) r.values = run_frf(s, *st, r.q0);
  if (const auto* st = std::get_if<SweepStudy>(&s.study)) r.values = run_sweep(s, *st, r.q0);
  if (const auto* st = std::get_if<CalibrationStudy>(&s.study))
    r.values = calibrate_dsa380(st->start, kThesisTable22Hz, s.contact_force, s.working_height);
  return r;
}

}  // namespace pcsim::simulation
