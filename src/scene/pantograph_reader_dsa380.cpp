// DSA-380 model files (geometry, bars, springs, damper; thesis Annex A) and its effects.
#include <cmath>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/pantograph_reader.hpp"

namespace pcsim::scene {

namespace {
double deg(const InputNode& n, const std::string& key, double fallback) {
  return n.get_real(key, Limit{3600.0, "deg"}, fallback) * M_PI / 180.0;
}

void load_geometry(const InputNode& g, pantograph::Dsa380Parameters* p) {
  g.allow_only({"x1", "y1", "L1", "L2", "L3", "L4", "L5", "L6", "L7", "L7p", "theta34_deg", "r",
                "theta_r_deg", "L1p", "theta_1p_deg", "x13", "y13", "lower_branch",
                "upper_branch"});
  p->x1 = g.get_real("x1", limits::pantograph_length);
  p->y1 = g.get_real("y1", limits::pantograph_length);
  p->L1 = g.get_positive("L1", limits::pantograph_length);
  p->L2 = g.get_positive("L2", limits::pantograph_length);
  p->L3 = g.get_positive("L3", limits::pantograph_length);
  p->L4 = g.get_positive("L4", limits::pantograph_length);
  p->L5 = g.get_positive("L5", limits::pantograph_length);
  p->L6 = g.get_positive("L6", limits::pantograph_length);
  p->L7 = g.get_positive("L7", limits::pantograph_length);
  p->L7p = g.get_real("L7p", limits::pantograph_length, 0.0);
  p->theta34 = deg(g, "theta34_deg", 180.0);
  p->r = g.get_positive("r", limits::pantograph_length);
  p->theta_r = deg(g, "theta_r_deg", 0.0);
  p->L1p = g.get_positive("L1p", limits::pantograph_length);
  p->theta_1p = deg(g, "theta_1p_deg", 0.0);
  p->x13 = g.get_real("x13", limits::pantograph_length);
  p->y13 = g.get_real("y13", limits::pantograph_length);
  // The lower loop fixed-1-2-3 (A.1, A.2) closes at some frame angle only if
  // the end of bar 1, |P1 + L1 e(θ)| from the origin, can lie strictly
  // between |L2 - L3| and L2 + L3 (a model fault, whatever the working height).
  const double rho = std::hypot(p->x1, p->y1);
  const double d_lo = std::abs(rho - p->L1), d_hi = rho + p->L1;
  if (!(d_hi > std::abs(p->L2 - p->L3) && d_lo < p->L2 + p->L3))
    g.fail_key(
        "L1",
        "the mechanism cannot be assembled at any frame angle: with L1 = " + format_number(p->L1) +
            " m the end of bar 1 lies " + format_number(d_lo) + " to " + format_number(d_hi) +
            " m from the lower hinge, bars L2 and L3 reach only " +
            format_number(std::abs(p->L2 - p->L3)) + " to " + format_number(p->L2 + p->L3) + " m");
  p->lower_branch = g.get_int("lower_branch", 1) >= 0 ? 1 : -1;
  p->upper_branch = g.get_int("upper_branch", 1) >= 0 ? 1 : -1;
}

// bellows: {characteristic: constant | {height: [...], force: [...]}, time_constant,
// valve_time_constant} (pantograph/bellows.hpp).
void load_bellows(const InputNode& b, pantograph::BellowsParameters* p) {
  b.allow_only({"characteristic", "time_constant", "valve_time_constant"});
  if (b.has("characteristic") && b["characteristic"].is_map()) {
    const auto c = b["characteristic"];
    c.allow_only({"height", "force"});
    p->heights = c["height"].as_doubles();
    p->forces = c["force"].as_doubles();
    if (p->heights.size() < 2 || p->heights.size() != p->forces.size())
      c.fail("needs height and force lists of the same length, at least 2 points");
    for (std::size_t i = 1; i < p->heights.size(); ++i)
      if (!(p->heights[i] > p->heights[i - 1])) c.fail_key("height", "heights must increase");
    for (double f : p->forces) {
      if (!(f > 0)) c.fail_key("force", "forces must be positive");
      if (!limit_violation(f, limits::force).empty())
        c.fail_key("force", limit_violation(f, limits::force));
    }
    for (double h : p->heights)
      if (!limit_violation(h, limits::pantograph_length).empty())
        c.fail_key("height", limit_violation(h, limits::pantograph_length));
  } else if (b.get_choice("characteristic", {"constant"}, "constant") != "constant") {
    b.fail_key("characteristic", "must be 'constant' or {height: [...], force: [...]}");
  }
  p->time_constant = b.get_nonnegative("time_constant", limits::time, 0.0);
  p->valve_time_constant = b.get_nonnegative("valve_time_constant", limits::time, 0.0);
  if (p->time_constant > 0 && !(p->valve_time_constant > 0))
    b.fail_key("valve_time_constant",
               "must be > 0 with a time_constant (the pressure loop is two lags in series)");
}
}  // namespace

pantograph::Dsa380Parameters load_dsa380_parameters(const InputNode& model) {
  model.allow_only({"kind", "name", "source", "geometry", "bars", "springs", "damper",
                    "aerodynamic", "gravity", "theta_guess_deg", "bellows"});
  pantograph::Dsa380Parameters p;
  p.name = model.get_string("name", "dsa380");
  load_geometry(model["geometry"], &p);
  const auto bars = model["bars"];
  if (!bars.is_sequence() || bars.size() != 7) bars.fail("must list the 7 bars in order");
  for (std::size_t i = 0; i < 7; ++i) {
    const auto b = bars.at(i);
    b.allow_only({"name", "mass", "inertia", "LG", "thetaG_deg"});
    p.m[i] = b.get_positive("mass", limits::mass);
    p.I[i] = b.get_nonnegative("inertia", limits::inertia);
    p.LG[i] = b.get_nonnegative("LG", limits::pantograph_length, 0.0);
    p.thetaG[i] = deg(b, "thetaG_deg", 0.0);
  }
  const auto s = model["springs"];
  s.allow_only({"kr", "theta_r0_deg", "kl", "kl3", "l10", "l20"});
  p.kr = s.get_nonnegative("kr", limits::rotational_stiffness);
  p.theta_r0 = deg(s, "theta_r0_deg", 0.0);
  p.kl = s.get_positive("kl", limits::stiffness);
  p.kl3 = s.get_nonnegative("kl3", limits::cubic_stiffness, 0.0);
  p.l10 = s.get_positive("l10", limits::pantograph_length);
  p.l20 = s.get_positive("l20", limits::pantograph_length, p.l10);
  if (model.has("damper")) {
    const auto d = model["damper"];
    d.allow_only({"c"});
    p.c = d.get_nonnegative("c", limits::damping);
  }
  if (model.has("aerodynamic")) {
    const auto a = model["aerodynamic"];
    a.allow_only({"a", "b", "c"});
    p.aero_a = a.get_real("a", limits::coefficient, 0.0);
    p.aero_b = a.get_real("b", limits::coefficient, 0.0);
    p.aero_c = a.get_real("c", limits::coefficient, 0.0);
  }
  if (model.has("bellows")) load_bellows(model["bellows"], &p.bellows);
  p.g = model.get_nonnegative("gravity", limits::gravity, 9.81);
  p.theta_guess = deg(model, "theta_guess_deg", 35.0);
  return p;
}

pantograph::Dsa380Effects load_dsa380_effects(const InputNode& effects) {
  using HeadRestraint = pantograph::Dsa380Effects::HeadRestraint;
  pantograph::Dsa380Effects e;
  effects.allow_only(
      {"aerodynamic", "head_restraint", "friction", "damper", "uplift_characteristic"});
  e.aerodynamic = effects.get_bool("aerodynamic", false);
  e.uplift_characteristic = effects.get_bool("uplift_characteristic", false);
  const std::string r =
      effects.get_choice("head_restraint", {"none", "rotation", "horizontal"}, "none");
  e.head_restraint = r == "rotation"     ? HeadRestraint::rotation
                     : r == "horizontal" ? HeadRestraint::horizontal
                                         : HeadRestraint::none;
  if (effects.has("friction")) {
    const auto f = effects["friction"];
    f.allow_only({"force", "kt"});
    e.friction_force = f.get_nonnegative("force", limits::force);
    e.friction_kt = f.get_positive("kt", Limit{100.0, "m/s"}, 5e-4);
    e.friction = e.friction_force > 0;
  }
  if (effects.has("damper")) {
    const auto d = effects["damper"];
    d.allow_only({"enabled", "one_way", "quadratic"});
    e.damper = d.get_bool("enabled", true);
    e.damper_one_way = d.get_bool("one_way", false);
    e.damper_quadratic = d.get_nonnegative("quadratic", Limit{1e8, "N s^2/m^2"}, 0.0);
  }
  return e;
}

}  // namespace pcsim::scene
