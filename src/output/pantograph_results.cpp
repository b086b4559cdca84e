#include "pcsim/output/pantograph_results.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/provenance.hpp"
#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/flexible_dsa380.hpp"

namespace pcsim::output {

namespace {

using namespace pcsim::pantograph;
using nlohmann::json;

// printf into a std::string (the log lines).
std::string format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
}

std::vector<double> to_vec(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

// Name of a mode. Rigid DSA-380: by its dominant coordinate. Flexible DSA-380: "bending of
// bar b" when most (> 50 %) of its strain energy ½φᵀKφ is in one bar's bending; else by
// where its kinetic energy ½φᵀMφ is largest, as the rigid model's modes: the bars (frame),
// the head's x10, y10 or θ7.
std::string mode_label(const PantographModel& m, const LinearModel& lin, const Mode& mode) {
  if (const auto* f = dynamic_cast<const FlexibleDsa380Pantograph*>(&m)) {
    const Eigen::VectorXd phi = mode.shape.real();
    const double strain = 0.5 * phi.dot(lin.K * phi);
    const auto E = f->bar_strain_energies(lin.q0, phi);
    for (int b = 0; b < 9; ++b)
      if (strain > 0 && E[b].bending > 0.5 * strain)
        return "bending of bar " + std::to_string(b + 1);
    double share[4];  // frame, head horizontal, head vertical, head rotation
    for (int i = 1; i < 4; ++i) share[i] = lin.M(i, i) * phi[i] * phi[i];
    share[0] =
        phi.dot(lin.M * phi) - phi.segment<3>(1).dot(lin.M.block<3, 3>(1, 1) * phi.segment<3>(1));
    const int best = static_cast<int>(std::max_element(share, share + 4) - share);
    return dsa380_mode_label(best);  // index = q index of θ (bars), x10, y10, θ7
  }
  return dynamic_cast<const Dsa380Pantograph*>(&m) ? dsa380_mode_label(mode.dominant_dof) : "";
}

// Bellows torque at the equilibrium (DSA-380 models).
double bellows_torque(const PantographModel& m) {
  if (const auto* d = dynamic_cast<const Dsa380Pantograph*>(&m)) return d->bellows_torque();
  if (const auto* f = dynamic_cast<const FlexibleDsa380Pantograph*>(&m)) return f->bellows_torque();
  return std::nan("");
}

json base_summary(const std::string& scene_name, const StudyScene& s, const StudyResult& r) {
  json j;
  j["scene"] = scene_name;
  j["model"] = s.model->kind();
  j["dof_names"] = s.model->dof_names();
  j["equilibrium"] = {{"contact_force_N", s.contact_force},
                      {"working_height_m", s.working_height},
                      {"q0", to_vec(r.q0)}};
  if (std::isfinite(bellows_torque(*s.model)))
    j["equilibrium"]["bellows_torque_Nm"] = bellows_torque(*s.model);
  if (auto* d = dynamic_cast<const Dsa380Pantograph*>(s.model.get()))
    j["equilibrium"]["head_descent_m"] = d->head_descent(s.contact_force);
  j["study"] = s.study_type;
  return j;
}

void write_history(H5File& h5, const std::string& group, const TimeHistory& h,
                   const PantographModel& m) {
  const size_t n = h.t.size(), d = m.dof_count();
  std::vector<double> q(n * d), qd(n * d), height(n);
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = 0; i < d; ++i) q[k * d + i] = h.q[k][i], qd[k * d + i] = h.qd[k][i];
    height[k] = h.q[k][m.contact_dof()] + m.contact_offset() + m.frame_height(h.t[k]);
  }
  const auto names = m.dof_names();
  h5.write(group + "/t", h.t, {"s", "time"});
  h5.write(group + "/q", q, n, d,
           {"m, rad", "generalised coordinates (lengths in m, angles in rad; see labels)", names});
  h5.write(group + "/qd", qd, n, d, {"m/s, rad/s", "their rates (see labels)", names});
  h5.write(group + "/contact_height", height, {"m", "height of the contact point"});
  h5.write(group + "/contact_force", h.contact_force,
           {"N", "contact force (downward on the head)"});
  h5.write(group + "/energy/kinetic", h.kinetic, {"J", "kinetic energy T"});
  h5.write(group + "/energy/potential", h.potential,
           {"J", "potential energy V (springs, gravity)"});
  h5.write(group + "/energy/work_dissipative", h.work_dissipative,
           {"J", "work of the dissipative forces since t = 0"});
  h5.write(group + "/energy/work_external", h.work_external,
           {"J", "work of the external forces since t = 0"});
  h5.write(group + "/energy/balance", h.energy_balance(),
           {"J", "energy balance (T + V) - (T + V)(0) - W_dissipative - W_external (thesis 2.34)"});
  h5.write_strings(group + "/dof_names", names, {"none", "names of the generalised coordinates"});
}

json balance_json(const TimeHistory& h) {
  const auto b = h.energy_balance();
  double bmax = 0, emin = 1e300, emax = -1e300;
  for (size_t k = 0; k < b.size(); ++k) {
    bmax = std::max(bmax, std::abs(b[k]));
    emin = std::min(emin, h.kinetic[k] + h.potential[k]);
    emax = std::max(emax, h.kinetic[k] + h.potential[k]);
  }
  return {{"max_abs_balance_J", bmax},
          {"energy_range_J", emax - emin},
          {"relative", emax > emin ? bmax / (emax - emin) : 0.0}};
}

// The linearised model has the model's DOFs, contact DOF and contact offset.
std::string write_time(OutputDir& out, const StudyScene& s, const TimeStudyResult& r, json& j) {
  const auto& study = std::get<TimeStudy>(s.study);
  H5File h5(out.file("time.h5"));
  stamp_provenance(h5, out.provenance());
  std::string log;
  for (const auto& run : r.runs) {
    write_history(h5, "/" + run.scheme, run.history, *s.model);
    const json balance = balance_json(run.history);
    j[run.scheme] = {{"steps", run.history.steps}, {"energy_balance", balance}};
    log += format("  %s: %ld steps, energy balance max %.3e of range %.3e J\n", run.scheme.c_str(),
                  run.history.steps, balance["max_abs_balance_J"].get<double>(),
                  balance["energy_range_J"].get<double>());
    if (run.has_linear) write_history(h5, "/" + run.scheme + "_linear", run.linear, *s.model);
  }
  j["dt"] = study.options.dt;
  j["t_end"] = study.options.t_end;
  return log;
}

void write_matrices(const LinearModel& lin, json& j) {
  j["M"] = std::vector<std::vector<double>>();
  for (int i = 0; i < lin.M.rows(); ++i) {
    j["M"].push_back(to_vec(lin.M.row(i).transpose()));
    j["C"].push_back(to_vec(lin.C.row(i).transpose()));
    j["K"].push_back(to_vec(lin.K.row(i).transpose()));
  }
}

std::string write_modes(const StudyScene& s, const ModesStudyResult& r, json& j) {
  const auto& und = r.undamped;
  const auto& names = r.linear.dof_names;
  std::vector<double> f, fd, zeta;
  json modes = json::array(), dmodes = json::array();
  std::string log;
  for (const auto& m : und) {
    f.push_back(m.frequency_hz);
    std::vector<double> shape;
    for (int i = 0; i < m.shape.size(); ++i) shape.push_back(m.shape[i].real());
    modes.push_back({{"frequency_hz", m.frequency_hz},
                     {"dominant_dof", names[m.dominant_dof]},
                     {"label", mode_label(*s.model, r.linear, m)},
                     {"shape", shape}});
    log += format("  mode %zu: %.4f Hz (undamped), %s %s\n", f.size(), m.frequency_hz,
                  names[m.dominant_dof].c_str(), mode_label(*s.model, r.linear, m).c_str());
  }
  std::vector<double> real_roots;  // overdamped: λ real (1/s)
  for (const auto& m : r.damped) {
    if (m.real_root) {
      real_roots.push_back(m.eigenvalue.real());
      continue;
    }
    fd.push_back(m.frequency_hz);
    zeta.push_back(m.damping_ratio);
    dmodes.push_back({{"frequency_hz", m.frequency_hz},
                      {"damping_ratio", m.damping_ratio},
                      {"dominant_dof", names[m.dominant_dof]},
                      {"label", mode_label(*s.model, r.linear, m)}});
  }
  for (size_t k = 0; k < fd.size(); ++k)
    log += format("  damped %zu: %.4f Hz, zeta %.4f\n", k + 1, fd[k], zeta[k]);
  j["pantograph_frequencies_hz"] = f;
  j["pantograph_damped_frequencies_hz"] = fd;
  j["pantograph_damping_ratios"] = zeta;  // of the oscillatory damped modes
  j["overdamped_real_roots"] = real_roots;
  j["undamped_modes"] = modes;
  j["damped_modes"] = dmodes;
  j["slepc_vs_eigen_max_relative_difference"] = r.slepc_vs_eigen_max_relative_difference;
  write_matrices(r.linear, j);
  if (dynamic_cast<const Dsa380Pantograph*>(s.model.get()) && f.size() == 4) {
    json table = json::array();
    for (int k = 0; k < 4; ++k)
      table.push_back({{"target_hz", kThesisTable22Hz[k]},
                       {"obtained_hz", f[k]},
                       {"error_percent", 100 * (f[k] / kThesisTable22Hz[k] - 1)},
                       {"mode", dsa380_mode_label(und[k].dominant_dof)}});
    j["table_2_2"] = table;
  }
  return log;
}

void write_complex(H5File& h5, const std::string& group, const std::vector<std::complex<double>>& h,
                   const char* unit, const std::string& what) {
  std::vector<double> re, im, mag;
  for (const auto& v : h)
    re.push_back(v.real()), im.push_back(v.imag()), mag.push_back(std::abs(v));
  h5.write(group + "/real", re, {unit, what + ", real part"});
  h5.write(group + "/imag", im, {unit, what + ", imaginary part"});
  h5.write(group + "/abs", mag, {unit, what + ", magnitude"});
}

void write_receptance(H5File& h5, const std::string& group,
                      const std::vector<std::complex<double>>& h) {
  write_complex(h5, group, h, "m/N",
                "receptance H_cc of the contact coordinate (" + group.substr(1) + ")");
}

std::string write_frf(OutputDir& out, const StudyScene& s, const FrfStudyResult& r, json& j) {
  H5File h5(out.file("frf.h5"));
  stamp_provenance(h5, out.provenance());
  h5.write("/frequency_hz", r.frequencies_hz, {"Hz", "frequencies of the FRF"});
  write_receptance(h5, "/direct", r.direct);
  if (r.symmetric) write_receptance(h5, "/modal", r.modal);
  j["frf"] = {{"dof", s.model->dof_names()[r.dof]}, {"points", r.frequencies_hz.size()}};
  std::string log = format("  H_cc over %zu frequencies\n", r.frequencies_hz.size());
  if (!r.transmissibility.empty()) {
    write_complex(h5, "/transmissibility", r.transmissibility, "m/m",
                  "base-to-head transmissibility z_c / z_b (direct)");
    j["frf"]["transmissibility"] = true;
    log += "  base-to-head transmissibility z_c / z_b: /transmissibility\n";
  }
  if (r.symmetric) {
    j["frf"]["direct_vs_modal_max_relative_difference"] = r.direct_vs_modal_max_relative_difference;
    log += format("  direct vs modal superposition: max relative difference %.3e\n",
                  r.direct_vs_modal_max_relative_difference);
  } else {
    log += "  non-symmetric (restrained) model: direct FRF only\n";
  }
  return log;
}

std::string write_sweep(OutputDir& out, const SweepStudyResult& r, json& j) {
  H5File h5(out.file("sweep.h5"));
  stamp_provenance(h5, out.provenance());
  h5.write("/frequency_hz", r.frequencies_hz, {"Hz", "excitation frequencies"});
  j["amplitudes_N"] = r.amplitudes;
  std::string log;
  for (const auto& c : r.curves) {
    h5.write(format("/%s/A_%g", c.group.c_str(), c.amplitude), c.response,
             {"m/N", format("steady-state peak-to-peak contact displacement / (2 x %g N), %s model",
                            c.amplitude, c.group.c_str())});
    log += format("  %s amplitude %g N: %zu frequencies\n", c.group.c_str(), c.amplitude,
                  r.frequencies_hz.size());
  }
  return log;
}

std::string write_calibration(const CalibrationResult& r, json& j) {
  j["calibrated"] = {{"kr", r.params.kr},
                     {"kl", r.params.kl},
                     {"l10", r.params.l10},
                     {"I7", r.params.I[6]},
                     {"newton_iterations", r.iterations}};
  json table = json::array();
  std::string log;
  for (size_t k = 0; k < r.obtained_hz.size(); ++k) {
    const char* mode = dsa380_mode_label(r.dominant_dof[k]);
    table.push_back(
        {{"target_hz", r.target_hz[k]}, {"obtained_hz", r.obtained_hz[k]}, {"mode", mode}});
    log += format("  target %.4f Hz  obtained %.6f Hz  (%s)\n", r.target_hz[k], r.obtained_hz[k],
                  mode);
  }
  j["table_2_2"] = table;
  log += format("  kr = %.10g N m/rad, kl = %.10g N/m, l10 = l20 = %.10g m, I7 = %.10g kg m2\n",
                r.params.kr, r.params.kl, r.params.l10, r.params.I[6]);
  return log;
}

}  // namespace

std::string write_pantograph_study(OutputDir& out, const std::string& scene_name,
                                   const StudyScene& scene, const StudyResult& result) {
  json j = base_summary(scene_name, scene, result);
  std::string log;
  if (const auto* r = std::get_if<TimeStudyResult>(&result.values))
    log = write_time(out, scene, *r, j);
  if (const auto* r = std::get_if<ModesStudyResult>(&result.values))
    log = write_modes(scene, *r, j);
  if (const auto* r = std::get_if<FrfStudyResult>(&result.values))
    log = write_frf(out, scene, *r, j);
  if (const auto* r = std::get_if<SweepStudyResult>(&result.values)) log = write_sweep(out, *r, j);
  if (const auto* r = std::get_if<CalibrationResult>(&result.values))
    log = write_calibration(*r, j);
  j["provenance"] = out.provenance();
  write_json(out.file("summary.json"), j);
  return log;
}

}  // namespace pcsim::output
