#include "pcsim/scene/pantograph_scene.hpp"

#include <cmath>

#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/scene/time_signal.hpp"

namespace pcsim::scene {

namespace {

using namespace pcsim::pantograph;

// Force from a file of "t, F" rows, interpolated linearly and held constant outside.
ForceHistory load_force_file(const InputNode& f) {
  const Samples s = load_samples(f, "force");
  return [s](double t) { return s.value(t); };
}

TimeStudy load_time_study(const InputNode& st) {
  st.allow_only({"type", "schemes", "dt", "t_end", "hht_alpha", "record_every", "force", "linear"});
  TimeStudy s;
  s.force = load_force_history(st["force"]);
  s.options.dt = st.get_positive("dt", limits::time_step, 1e-3);
  s.options.t_end = st.get_positive("t_end", limits::time, 1.0);
  s.options.hht_alpha = st.get_nonnegative("hht_alpha", 0.05);
  s.options.record_every = static_cast<int>(st.get_int("record_every", 1));
  if (st.has("schemes")) {
    s.schemes.clear();
    const auto l = st["schemes"];
    for (size_t i = 0; i < l.size(); ++i) {
      const std::string sch = l.at(i).as_string();
      if (sch != "rk4" && sch != "hht") l.at(i).fail("scheme must be rk4 or hht");
      s.schemes.push_back(sch);
    }
  }
  s.linear = st.get_bool("linear", false);
  return s;
}

// Log-spaced frequencies f_min_hz .. f_max_hz.
std::vector<double> load_frequency_grid(const InputNode& st) {
  const double f0 = st.get_positive("f_min_hz", limits::frequency, 0.1),
               f1 = st.get_positive("f_max_hz", limits::frequency, 20.0);
  const long n = st.get_int("points", 400);
  if (n < 2 || f1 <= f0) st.fail("need points >= 2 and f_max_hz > f_min_hz");
  std::vector<double> f(n);
  for (long k = 0; k < n; ++k) f[k] = f0 * std::pow(f1 / f0, double(k) / (n - 1));
  return f;
}

SweepStudy load_sweep_study(const InputNode& st) {
  st.allow_only({"type", "f_min_hz", "f_max_hz", "points", "amplitudes", "dt", "scheme",
                 "hht_alpha", "settle_s", "settle_periods", "measure_periods", "linear",
                 "start_on_linear_steady_state"});
  SweepStudy s;
  s.frequencies_hz = load_frequency_grid(st);
  s.amplitudes = st["amplitudes"].as_doubles();
  s.dt = st.get_positive("dt", limits::time_step, 1e-3);
  s.scheme = st.get_choice("scheme", {"rk4", "hht"}, "rk4");
  s.hht_alpha = st.get_nonnegative("hht_alpha", 0.05);
  s.settle_s = st.get_nonnegative("settle_s", limits::time, 10.0);
  s.settle_periods = st.get_nonnegative("settle_periods", Limit{1e6, ""}, 20.0);
  s.measure_periods = st.get_positive("measure_periods", Limit{1e6, ""}, 5.0);
  s.linear = st.get_bool("linear", false);
  s.start_on_linear_steady_state = st.get_bool("start_on_linear_steady_state", true);
  return s;
}

CalibrationStudy load_calibration_study(const InputNode& st, const PantographModel& model) {
  st.allow_only({"type", "start"});
  const auto* d = dynamic_cast<const Dsa380Pantograph*>(&model);
  if (!d) st.fail("calibrate needs a dsa380 model");
  CalibrationStudy s{d->parameters()};
  Dsa380Parameters& p = s.start;
  if (st.has("start")) {
    const auto a = st["start"];
    a.allow_only({"kr", "kl", "l10", "I7"});
    p.kr = a.get_positive("kr", limits::rotational_stiffness, p.kr);
    p.kl = a.get_positive("kl", limits::stiffness, p.kl);
    p.l10 = p.l20 = a.get_positive("l10", limits::pantograph_length, p.l10);
    p.I[6] = a.get_positive("I7", limits::inertia, p.I[6]);
  }
  return s;
}

Study load_study(const InputNode& st, const std::string& type, const PantographModel& model) {
  if (type == "time") return load_time_study(st);
  if (type == "modes") {
    st.allow_only({"type", "f_max_hz"});
    return ModesStudy{st.get_nonnegative("f_max_hz", limits::frequency, 0.0)};
  }
  if (type == "frf") {
    st.allow_only({"type", "f_min_hz", "f_max_hz", "points"});
    return FrfStudy{load_frequency_grid(st)};
  }
  if (type == "sweep") return load_sweep_study(st);
  return load_calibration_study(st, model);
}

}  // namespace

ForceHistory load_force_history(const InputNode& f) {
  const std::string type = f.get_choice("type", {"constant", "harmonic", "file"}, "constant");
  if (type == "constant") {
    f.allow_only({"type", "value"});
    const double v = f.get_real("value", limits::force);
    return [v](double) { return v; };
  }
  if (type == "harmonic") {
    f.allow_only({"type", "mean", "amplitude", "frequency_hz"});
    const double m = f.get_real("mean", limits::force), a = f.get_real("amplitude", limits::force),
                 w = 2 * M_PI * f.get_positive("frequency_hz", limits::frequency);
    return [m, a, w](double t) { return m + a * std::sin(w * t); };
  }
  f.allow_only({"type", "file"});
  return load_force_file(f);
}

StudyScene load_pantograph_study_scene(const InputNode& scene) {
  scene.allow_only({"name", "description", "pantograph", "speed_kmh", "equilibrium", "study"});
  const auto st = scene["study"];
  StudyScene s;
  s.study_type = st.get_choice("type", {"time", "modes", "frf", "sweep", "calibrate"}, "");
  if (s.study_type.empty()) st.fail_key("type", "required key is missing");
  s.speed = scene.get_nonnegative("speed_kmh", limits::speed_kmh, 0.0) / 3.6;
  s.model = load_pantograph(scene["pantograph"], s.speed);
  const InputNode e = scene.has("equilibrium")
                          ? scene["equilibrium"]
                          : InputNode(YAML::Node(), scene.file(), "equilibrium");
  if (scene.has("equilibrium")) {
    e.allow_only({"contact_force", "working_height"});
    s.contact_force = e.get_real("contact_force", limits::force, 120.0);
    s.working_height = e.get_real("working_height", limits::pantograph_length, 1.2);
  }
  check_working_height(e, *s.model, s.contact_force, s.working_height, e.has("working_height"));
  s.study = load_study(st, s.study_type, *s.model);
  // The linearised model and the other studies do not take the base motion.
  const auto* time = std::get_if<TimeStudy>(&s.study);
  if (scene["pantograph"].has("base_motion") && (!time || time->linear))
    scene["pantograph"].fail_key("base_motion",
                                 "only for time studies without 'linear' (an frf study gives the "
                                 "base-to-head transmissibility)");
  return s;
}

}  // namespace pcsim::scene
