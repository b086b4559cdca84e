// `pcsim pantograph SCENE.yaml`: studies of the pantograph alone (thesis chapter 2).
//
// Scene:
//   name: ...
//   pantograph: {model: <meshes/pantographs/*.yaml relative to the scene>, effects: {...}}
//   speed_kmh: 0                               # for the aerodynamic force only
//   equilibrium: {contact_force: 120, working_height: 1.2}
//   study: {type: time|modes|frf|sweep|calibrate, ...}
// Output (in an OutputDir): summary.json, HDF5 histories/curves.
#include <cmath>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/pantograph/calibration.hpp"
#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/linear.hpp"
#include "pcsim/pantograph/time_integration.hpp"

namespace {

using namespace pcsim;
using namespace pcsim::pantograph;
using nlohmann::json;
using pcsim::app::CommandContext;

struct Setup {
  std::unique_ptr<PantographModel> model;
  double F0 = 120, h0 = 1.2, speed = 0;
  Eigen::VectorXd q0;
};

Setup make_setup(const InputNode& scene) {
  Setup s;
  s.speed = scene.get_nonnegative("speed_kmh", 0.0) / 3.6;
  s.model = make_pantograph(scene["pantograph"], s.speed);
  if (scene.has("equilibrium")) {
    const auto e = scene["equilibrium"];
    e.allow_only({"contact_force", "working_height"});
    s.F0 = e.get_double("contact_force", 120.0);
    s.h0 = e.get_double("working_height", 1.2);
  }
  s.q0 = s.model->static_equilibrium(s.F0, s.h0);
  return s;
}

// Downward contact force history: constant, harmonic F0 + A sin(2πft), step, or a file.
ForceHistory make_force(const InputNode& f) {
  const std::string type = f.get_choice("type", {"constant", "harmonic", "file"}, "constant");
  if (type == "constant") {
    f.allow_only({"type", "value"});
    const double v = f.get_double("value");
    return [v](double) { return v; };
  }
  if (type == "harmonic") {
    f.allow_only({"type", "mean", "amplitude", "frequency_hz"});
    const double m = f.get_double("mean"), a = f.get_double("amplitude"),
                 w = 2 * M_PI * f.get_positive("frequency_hz");
    return [m, a, w](double t) { return m + a * std::sin(w * t); };
  }
  f.allow_only({"type", "file"});
  const std::string path = f.resolve_path(f.get_string("file"));
  std::ifstream in(path);
  if (!in) f.fail_key("file", "cannot open " + path);
  std::vector<double> ts, fs;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream ss(line);
    double t, v;
    if (!(ss >> t >> v)) f.fail_key("file", "bad line '" + line + "' (expected: t, force)");
    if (!ts.empty() && t <= ts.back()) f.fail_key("file", "times must increase");
    ts.push_back(t);
    fs.push_back(v);
  }
  if (ts.empty()) f.fail_key("file", "no samples");
  return [ts, fs](double t) {  // linear interpolation, held constant outside
    if (t <= ts.front()) return fs.front();
    if (t >= ts.back()) return fs.back();
    const size_t k = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin();
    const double w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
    return (1 - w) * fs[k - 1] + w * fs[k];
  };
}

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
}

void write_history(H5File& h5, const std::string& group, const TimeHistory& h,
                   const PantographModel& m) {
  const size_t n = h.t.size(), d = m.dof_count();
  std::vector<double> q(n * d), qd(n * d), height(n);
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = 0; i < d; ++i) q[k * d + i] = h.q[k][i], qd[k * d + i] = h.qd[k][i];
    height[k] = h.q[k][m.contact_dof()] + m.contact_offset();
  }
  h5.write(group + "/t", h.t);
  h5.write(group + "/q", q, n, d);
  h5.write(group + "/qd", qd, n, d);
  h5.write(group + "/contact_height", height);
  h5.write(group + "/contact_force", h.contact_force);
  h5.write(group + "/energy/kinetic", h.kinetic);
  h5.write(group + "/energy/potential", h.potential);
  h5.write(group + "/energy/work_dissipative", h.work_dissipative);
  h5.write(group + "/energy/work_external", h.work_external);
  h5.write(group + "/energy/balance", h.energy_balance());
  h5.write_strings(group + "/dof_names", m.dof_names());
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

std::vector<double> to_vec(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

json base_summary(const CommandContext& ctx, const InputNode& scene, const Setup& s) {
  json j;
  j["scene"] = ctx.scene_name(scene);
  j["model"] = s.model->kind();
  j["dof_names"] = s.model->dof_names();
  j["equilibrium"] = {{"contact_force_N", s.F0}, {"working_height_m", s.h0}, {"q0", to_vec(s.q0)}};
  if (auto* d = dynamic_cast<const Dsa380Pantograph*>(s.model.get())) {
    j["equilibrium"]["bellows_torque_Nm"] = d->bellows_torque();
    j["equilibrium"]["head_descent_m"] = d->head_descent(s.F0);
  }
  return j;
}

// ---- studies ----

int study_time(const CommandContext& ctx, const InputNode& scene, const InputNode& st, Setup& s,
               OutputDir& out) {
  st.allow_only({"type", "schemes", "dt", "t_end", "hht_alpha", "record_every", "force", "linear"});
  const ForceHistory force = make_force(st["force"]);
  TimeOptions opt;
  opt.dt = st.get_positive("dt", 1e-3);
  opt.t_end = st.get_positive("t_end", 1.0);
  opt.hht_alpha = st.get_nonnegative("hht_alpha", 0.05);
  opt.record_every = static_cast<int>(st.get_int("record_every", 1));
  std::vector<std::string> schemes = {"rk4"};
  if (st.has("schemes")) {
    schemes.clear();
    const auto l = st["schemes"];
    for (size_t i = 0; i < l.size(); ++i) {
      const std::string sch = l.at(i).as_string();
      if (sch != "rk4" && sch != "hht") l.at(i).fail("scheme must be rk4 or hht");
      schemes.push_back(sch);
    }
  }
  json j = base_summary(ctx, scene, s);
  j["study"] = "time";
  H5File h5(out.file("time.h5"));
  const Eigen::VectorXd v0 = Eigen::VectorXd::Zero(s.model->dof_count());
  for (const auto& sch : schemes) {
    opt.scheme = sch;
    const auto h = integrate_pantograph(*s.model, s.q0, v0, force, opt);
    write_history(h5, "/" + sch, h, *s.model);
    j[sch] = {{"steps", h.steps}, {"energy_balance", balance_json(h)}};
    app::print0(ctx, "  %s: %ld steps, energy balance max %.3e of range %.3e J\n", sch.c_str(),
                h.steps, j[sch]["energy_balance"]["max_abs_balance_J"].get<double>(),
                j[sch]["energy_balance"]["energy_range_J"].get<double>());
    if (st.get_bool("linear", false)) {
      LinearisedPantograph lin(linearise(*s.model, s.q0), s.model->contact_dof(),
                               s.model->contact_offset(), s.F0);
      const auto hl = integrate_pantograph(lin, s.q0, v0, force, opt);
      write_history(h5, "/" + sch + "_linear", hl, lin);
    }
  }
  j["dt"] = opt.dt;
  j["t_end"] = opt.t_end;
  write_json(out.file("summary.json"), j);
  return 0;
}

const char* mode_label(const std::string& kind, int dof) {
  if (kind != "dsa380") return "";
  static const char* labels[4] = {"frame", "head horizontal", "head vertical", "head rotation"};
  return dof >= 0 && dof < 4 ? labels[dof] : "";
}

int study_modes(const CommandContext& ctx, const InputNode& scene, const InputNode& st, Setup& s,
                OutputDir& out) {
  st.allow_only({"type"});
  const LinearModel lin = linearise(*s.model, s.q0);
  const auto und = undamped_modes_slepc(lin), dam = damped_modes_slepc(lin);
  const auto und_e = undamped_modes_eigen(lin), dam_e = damped_modes_eigen(lin);
  json j = base_summary(ctx, scene, s);
  j["study"] = "modes";
  std::vector<double> f, fd, zeta;
  json modes = json::array();
  double diff = 0;
  for (size_t k = 0; k < und.size(); ++k) {
    f.push_back(und[k].frequency_hz);
    std::vector<double> shape;
    for (int i = 0; i < und[k].shape.size(); ++i) shape.push_back(und[k].shape[i].real());
    modes.push_back({{"frequency_hz", und[k].frequency_hz},
                     {"dominant_dof", lin.dof_names[und[k].dominant_dof]},
                     {"label", mode_label(s.model->kind(), und[k].dominant_dof)},
                     {"shape", shape}});
    if (k < und_e.size())
      diff = std::max(diff,
                      std::abs(und[k].frequency_hz - und_e[k].frequency_hz) / und[k].frequency_hz);
  }
  json dmodes = json::array();
  std::vector<double> real_roots;  // overdamped: λ real (1/s)
  for (size_t k = 0; k < dam.size(); ++k) {
    if (dam[k].real_root) {
      real_roots.push_back(dam[k].eigenvalue.real());
      continue;
    }
    fd.push_back(dam[k].frequency_hz);
    zeta.push_back(dam[k].damping_ratio);
    dmodes.push_back({{"frequency_hz", dam[k].frequency_hz},
                      {"damping_ratio", dam[k].damping_ratio},
                      {"dominant_dof", lin.dof_names[dam[k].dominant_dof]}});
    if (k < dam_e.size())
      diff = std::max(diff,
                      std::abs(dam[k].frequency_hz - dam_e[k].frequency_hz) / dam[k].frequency_hz);
  }
  j["pantograph_frequencies_hz"] = f;
  j["pantograph_damped_frequencies_hz"] = fd;
  j["pantograph_damping_ratios"] = zeta;  // of the oscillatory damped modes
  j["overdamped_real_roots"] = real_roots;
  j["undamped_modes"] = modes;
  j["damped_modes"] = dmodes;
  j["slepc_vs_eigen_max_relative_difference"] = diff;
  j["M"] = std::vector<std::vector<double>>();
  for (int i = 0; i < lin.M.rows(); ++i) {
    j["M"].push_back(to_vec(lin.M.row(i).transpose()));
    j["C"].push_back(to_vec(lin.C.row(i).transpose()));
    j["K"].push_back(to_vec(lin.K.row(i).transpose()));
  }
  if (s.model->kind() == "dsa380" && f.size() == 4) {
    json table = json::array();
    for (int k = 0; k < 4; ++k)
      table.push_back({{"target_hz", kThesisTable22Hz[k]},
                       {"obtained_hz", f[k]},
                       {"error_percent", 100 * (f[k] / kThesisTable22Hz[k] - 1)},
                       {"mode", mode_label("dsa380", und[k].dominant_dof)}});
    j["table_2_2"] = table;
  }
  for (size_t k = 0; k < f.size(); ++k)
    app::print0(ctx, "  mode %zu: %.4f Hz (undamped), %s\n", k + 1, f[k],
                modes[k]["dominant_dof"].get<std::string>().c_str());
  for (size_t k = 0; k < fd.size(); ++k)
    app::print0(ctx, "  damped %zu: %.4f Hz, zeta %.4f\n", k + 1, fd[k], zeta[k]);
  write_json(out.file("summary.json"), j);
  return 0;
}

std::vector<double> frequency_grid(const InputNode& st) {
  const double f0 = st.get_positive("f_min_hz", 0.1), f1 = st.get_positive("f_max_hz", 20.0);
  const long n = st.get_int("points", 400);
  if (n < 2 || f1 <= f0) st.fail("need points >= 2 and f_max_hz > f_min_hz");
  std::vector<double> f(n);
  for (long k = 0; k < n; ++k) f[k] = f0 * std::pow(f1 / f0, double(k) / (n - 1));
  return f;
}

int study_frf(const CommandContext& ctx, const InputNode& scene, const InputNode& st, Setup& s,
              OutputDir& out) {
  st.allow_only({"type", "f_min_hz", "f_max_hz", "points"});
  const auto freqs = frequency_grid(st);
  const LinearModel lin = linearise(*s.model, s.q0);
  const int c = s.model->contact_dof();
  const bool symmetric = lin.M.isApprox(lin.M.transpose()) && lin.K.isApprox(lin.K.transpose());
  const auto dam = damped_modes_slepc(lin);
  std::vector<double> re, im, mag, mre, mim, mmag;
  double maxrel = 0;
  for (double f : freqs) {
    const double w = 2 * M_PI * f;
    const auto h = frf_direct(lin, c, c, w);  // H33 (2.36)
    re.push_back(h.real()), im.push_back(h.imag()), mag.push_back(std::abs(h));
    if (symmetric) {
      const auto hm = frf_modal(lin, dam, c, c, w);  // (2.40)
      mre.push_back(hm.real()), mim.push_back(hm.imag()), mmag.push_back(std::abs(hm));
      maxrel = std::max(maxrel, std::abs(h - hm) / std::abs(h));
    }
  }
  H5File h5(out.file("frf.h5"));
  h5.write("/frequency_hz", freqs);
  h5.write("/direct/real", re);
  h5.write("/direct/imag", im);
  h5.write("/direct/abs", mag);
  if (symmetric) {
    h5.write("/modal/real", mre);
    h5.write("/modal/imag", mim);
    h5.write("/modal/abs", mmag);
  }
  json j = base_summary(ctx, scene, s);
  j["study"] = "frf";
  j["frf"] = {{"dof", s.model->dof_names()[c]}, {"points", freqs.size()}};
  if (symmetric) j["frf"]["direct_vs_modal_max_relative_difference"] = maxrel;
  app::print0(ctx, "  H_cc over %zu frequencies\n", freqs.size());
  if (symmetric)
    app::print0(ctx, "  direct vs modal superposition: max relative difference %.3e\n", maxrel);
  else
    app::print0(ctx, "  non-symmetric (restrained) model: direct FRF only\n");
  write_json(out.file("summary.json"), j);
  return 0;
}

// Nonlinear "FRF": peak-to-peak of the contact coordinate in steady state under
// F0 + A sin(2πft), divided by 2A (thesis 2.3.3).
int study_sweep(const CommandContext& ctx, const InputNode& scene, const InputNode& st, Setup& s,
                OutputDir& out) {
  st.allow_only({"type", "f_min_hz", "f_max_hz", "points", "amplitudes", "dt", "settle_s",
                 "settle_periods", "measure_periods", "linear", "start_on_linear_steady_state"});
  const auto freqs = frequency_grid(st);
  const std::vector<double> amps = st["amplitudes"].as_doubles();
  const double dt = st.get_positive("dt", 1e-3), settle = st.get_nonnegative("settle_s", 10.0);
  const double settle_periods = st.get_nonnegative("settle_periods", 20.0);
  const double measure = st.get_positive("measure_periods", 5.0);
  const int c = s.model->contact_dof();
  const LinearModel lin = linearise(*s.model, s.q0);
  std::unique_ptr<PantographModel> lin_model;
  if (st.get_bool("linear", false))
    lin_model = std::make_unique<LinearisedPantograph>(lin, c, s.model->contact_offset(), s.F0);
  // Start every run on the linear steady state Δq(t) = Im(X e^{iωt}),
  // X = [K + iωC − ω²M]⁻¹ (−A e_c), so that the lightly damped head modes start with
  // (almost) no free vibration.
  const bool start_steady = st.get_bool("start_on_linear_steady_state", true);
  auto initial = [&](double A, double w, Eigen::VectorXd* q, Eigen::VectorXd* v) {
    *q = s.q0;
    v->setZero(s.q0.size());
    if (!start_steady) return;
    const std::complex<double> I(0, 1);
    const Eigen::MatrixXcd D = lin.K.cast<std::complex<double>>() +
                               I * w * lin.C.cast<std::complex<double>>() -
                               w * w * lin.M.cast<std::complex<double>>();
    Eigen::VectorXcd f = Eigen::VectorXcd::Zero(s.q0.size());
    f[c] = -A;
    const Eigen::VectorXcd X = D.fullPivLu().solve(f);
    *q += X.imag();
    *v = w * X.real();
  };
  H5File h5(out.file("sweep.h5"));
  h5.write("/frequency_hz", freqs);
  json j = base_summary(ctx, scene, s);
  j["study"] = "sweep";
  j["amplitudes_N"] = amps;
  for (int pass = 0; pass < (lin_model ? 2 : 1); ++pass) {
    const PantographModel& m = pass == 0 ? *s.model : *lin_model;
    const std::string group = pass == 0 ? "/nonlinear" : "/linear";
    for (double A : amps) {
      std::vector<double> H;
      for (double f : freqs) {
        const double period = 1.0 / f;
        const double t_meas0 = std::max(settle, settle_periods * period);
        TimeOptions opt;
        opt.dt = dt;
        opt.t_end = t_meas0 + measure * period;
        const double F0 = s.F0, w = 2 * M_PI * f;
        double value = std::nan("");
        try {
          Eigen::VectorXd qs, vs;
          initial(A, w, &qs, &vs);
          const auto h = integrate_pantograph(
              m, qs, vs, [=](double t) { return F0 + A * std::sin(w * t); }, opt);
          double lo = 1e300, hi = -1e300;
          for (size_t k = 0; k < h.t.size(); ++k)
            if (h.t[k] >= t_meas0) lo = std::min(lo, h.q[k][c]), hi = std::max(hi, h.q[k][c]);
          value = (hi - lo) / (2 * A);
        } catch (const SolverError&) {
          // left as NaN: the response diverged (e.g. head overturning without restraint)
        }
        H.push_back(value);
      }
      char name[64];
      std::snprintf(name, sizeof name, "%s/A_%g", group.c_str(), A);
      h5.write(name, H);
      app::print0(ctx, "  %s amplitude %g N: %zu frequencies\n", group.c_str() + 1, A,
                  freqs.size());
    }
  }
  write_json(out.file("summary.json"), j);
  return 0;
}

int study_calibrate(const CommandContext& ctx, const InputNode& scene, const InputNode& st,
                    Setup& s, OutputDir& out) {
  st.allow_only({"type", "start"});
  auto* d = dynamic_cast<Dsa380Pantograph*>(s.model.get());
  if (!d) st.fail("calibrate needs a dsa380 model");
  Dsa380Parameters p = d->parameters();
  if (st.has("start")) {
    const auto a = st["start"];
    a.allow_only({"kr", "kl", "l10", "I7"});
    p.kr = a.get_positive("kr", p.kr);
    p.kl = a.get_positive("kl", p.kl);
    p.l10 = p.l20 = a.get_positive("l10", p.l10);
    p.I[6] = a.get_positive("I7", p.I[6]);
  }
  const auto res = calibrate_dsa380(p, kThesisTable22Hz, s.F0, s.h0);
  json j = base_summary(ctx, scene, s);
  j["study"] = "calibrate";
  j["calibrated"] = {{"kr", res.params.kr},
                     {"kl", res.params.kl},
                     {"l10", res.params.l10},
                     {"I7", res.params.I[6]},
                     {"newton_iterations", res.iterations}};
  json table = json::array();
  for (size_t k = 0; k < res.obtained_hz.size(); ++k) {
    table.push_back({{"target_hz", res.target_hz[k]},
                     {"obtained_hz", res.obtained_hz[k]},
                     {"mode", mode_label("dsa380", res.dominant_dof[k])}});
    app::print0(ctx, "  target %.4f Hz  obtained %.6f Hz  (%s)\n", res.target_hz[k],
                res.obtained_hz[k], mode_label("dsa380", res.dominant_dof[k]));
  }
  j["table_2_2"] = table;
  app::print0(ctx, "  kr = %.10g N m/rad, kl = %.10g N/m, l10 = l20 = %.10g m, I7 = %.10g kg m2\n",
              res.params.kr, res.params.kl, res.params.l10, res.params.I[6]);
  write_json(out.file("summary.json"), j);
  return 0;
}

int run_pantograph(const CommandContext& ctx) {
  const auto scene = InputNode::load_file(ctx.scene_path);
  scene.allow_only({"name", "pantograph", "speed_kmh", "equilibrium", "study"});
  const auto st = scene["study"];
  const std::string type =
      st.get_choice("type", {"time", "modes", "frf", "sweep", "calibrate"}, "");
  Setup s = make_setup(scene);
  OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim pantograph: scene '%s', %s model, study %s\n",
              ctx.scene_name(scene).c_str(), s.model->kind().c_str(), type.c_str());
  // The pantograph alone is tiny: rank 0 does the work; the others wait for its outcome.
  int rc = 0;
  app::on_rank0(ctx, [&] {
    if (type == "time") rc = study_time(ctx, scene, st, s, out);
    if (type == "modes") rc = study_modes(ctx, scene, st, s, out);
    if (type == "frf") rc = study_frf(ctx, scene, st, s, out);
    if (type == "sweep") rc = study_sweep(ctx, scene, st, s, out);
    if (type == "calibrate") rc = study_calibrate(ctx, scene, st, s, out);
  });
  out.commit();
  app::print0(ctx, "results in %s\n", out.final_dir().c_str());
  return rc;
}

}  // namespace

PCSIM_COMMAND("pantograph", "pantograph alone: time response, modes, FRFs, calibration",
              run_pantograph);
