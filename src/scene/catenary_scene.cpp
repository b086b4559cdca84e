#include "pcsim/scene/catenary_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/design_reader.hpp"

namespace pcsim::scene {

using namespace pcsim::catenary;

void check_scene_sections(const InputNode& scene) {
  scene.allow_only({"name", "description", "catenary", "modes", "pantographs", "simulation",
                    "effects", "contact", "analysis", "output", "elasticity", "window",
                    "assessment", "conditions"});
}

namespace {

constexpr double kMaxTemperatureChange =
    100;  // [K]: -40..+80 C about a design temperature of 10-20 C

ElasticityRequest read_elasticity(const InputNode& e, const CatenaryMesh& mesh) {
  e.allow_only({"force", "from_x", "to_x", "step"});
  if (mesh.contact_wire_list().empty() || mesh.support_x.size() < 2)
    e.fail("needs a parametric design (contact wire and supports)");
  ElasticityRequest r;
  r.force = e.get_positive("force", limits::force, 100.0);
  r.from_x = e.get_double("from_x");
  r.to_x = e.get_double("to_x");
  r.step = e.get_positive("step", limits::distance, 1.0);
  const double lo = mesh.support_x.front(), hi = mesh.support_x.back();
  if (!(r.from_x > lo && r.from_x < hi))
    e.fail_key("from_x",
               "must lie inside the line (" + format_number(lo) + ", " + format_number(hi) + ") m");
  if (!(r.to_x >= r.from_x && r.to_x < hi))
    e.fail_key("to_x", "must lie between from_x and the line's end (" + format_number(hi) + " m)");
  if ((r.to_x - r.from_x) / r.step > 10000)
    e.fail_key("step", "gives more than 10000 points: one static solution each");
  return r;
}

// The ice (kg/m per wire kind): a kind the design does not have is an error.
IceLoad read_ice(const InputNode& i, const CatenaryMesh& mesh) {
  i.allow_only({"contact", "messenger", "stitch"});
  IceLoad ice;
  const std::pair<const char*, WireKind> kinds[] = {{"contact", WireKind::contact},
                                                    {"messenger", WireKind::messenger},
                                                    {"stitch", WireKind::stitch}};
  for (const auto& [key, kind] : kinds) {
    if (!i.has(key)) continue;
    const double m = i.get_nonnegative(key, limits::mass_per_length);
    const bool wire = std::any_of(mesh.wires.begin(), mesh.wires.end(),
                                  [&](const Wire& w) { return w.kind == kind; });
    const bool stitch_bar =
        kind == WireKind::stitch &&
        std::any_of(mesh.bars.begin(), mesh.bars.end(),
                    [](const BarElement& b) { return b.kind == BarKind::stitch; });
    if (m > 0 && !wire && !stitch_bar)
      i.fail_key(key, std::string("the design has no ") + key + " wire");
    (kind == WireKind::contact     ? ice.contact
     : kind == WireKind::messenger ? ice.messenger
                                   : ice.stitch) = m;
  }
  return ice;
}

// EN 1991-1-4 terrain categories (Table 4.1): roughness length z0 and
// minimum height zmin [m].
struct Terrain {
  const char* name;
  double z0, zmin;
};
constexpr Terrain kTerrains[] = {
    {"0", 0.003, 1}, {"I", 0.01, 1}, {"II", 0.05, 2}, {"III", 0.3, 5}, {"IV", 1.0, 10}};

// The terrain (EN 1991-1-4) at the wires' height: 'conditions.wind.terrain_category',
// 'height' (z, at least the category's zmin).
struct Site {
  const Terrain* terrain;
  double z;
};

Site read_site(const InputNode& w) {
  const std::string category =
      w.get_choice("terrain_category", {"0", "I", "II", "III", "IV"}, "II");
  const Terrain* terrain = kTerrains;
  while (category != terrain->name) ++terrain;
  return {terrain, std::max(w.get_positive("height", limits::height, 6.0), terrain->zmin)};
}

// The turbulence (docs/conditions.md, "Turbulence"); defaults of the
// intensity and length scale from the site by EN 1991-1-4: I_v = 1 / ln(z / z0)
// (4.7, k_I = c0 = 1), L = 300 (z / 200)^alpha with alpha = 0.67 + 0.05 ln z0 (B.2).
TurbulenceSettings read_turbulence(const InputNode& t, const Site& site) {
  t.allow_only({"intensity", "length_scale", "vertical_ratio", "coherence_decay", "seed",
                "grid_spacing", "time_step"});
  TurbulenceSettings s;
  s.on = true;
  const double z0 = site.terrain->z0;
  s.intensity = t.get_positive("intensity", 1.0 / std::log(site.z / z0));
  if (s.intensity > 1) t.fail_key("intensity", "must be at most 1 (sigma_u / V)");
  s.length_scale = t.get_positive("length_scale", limits::distance,
                                  300 * std::pow(site.z / 200, 0.67 + 0.05 * std::log(z0)));
  s.vertical_ratio = t.get_nonnegative("vertical_ratio", limits::coefficient, s.vertical_ratio);
  s.coherence_decay = t.get_positive("coherence_decay", limits::coefficient, s.coherence_decay);
  const long seed = t.get_int("seed", 1);
  if (seed < 0) t.fail_key("seed", "must not be negative");
  s.seed = static_cast<unsigned long>(seed);
  s.grid_spacing = t.get_positive("grid_spacing", limits::distance, s.grid_spacing);
  s.time_step = t.get_positive("time_step", limits::time_step, s.time_step);
  return s;
}

// The mean wind speed at the wires: 'speed', or from the basic wind speed
// v_b by EN 1991-1-4 (4.3-4.5, c0 = 1): v_m = k_r ln(z / z0) v_b,
// k_r = 0.19 (z0 / 0.05)^0.07.
double read_mean_speed(const InputNode& w, const Site& site) {
  if (w.has("speed") == w.has("basic_speed"))
    w.fail(
        "needs exactly one of 'speed' (the mean wind at the wires) and 'basic_speed' "
        "(EN 1991-1-4's v_b)");
  if (w.has("speed")) return w.get_nonnegative("speed", limits::wind_speed);
  const double z0 = site.terrain->z0;
  const double vb = w.get_nonnegative("basic_speed", limits::wind_speed);
  return 0.19 * std::pow(z0 / 0.05, 0.07) * std::log(site.z / z0) * vb;
}

// The mean wind and the blow-off check's widths (docs/conditions.md).
WindLoad read_wind(const InputNode& w) {
  w.allow_only({"speed", "basic_speed", "terrain_category", "height", "direction_deg",
                "air_density", "working_half_width", "vehicle_sway", "track_tolerance",
                "turbulence"});
  WindLoad wind;
  const Site site = read_site(w);
  if (w.has("turbulence")) wind.turbulence = read_turbulence(w["turbulence"], site);
  wind.speed = read_mean_speed(w, site);
  wind.direction_deg = w.get_double("direction_deg", wind.direction_deg);
  if (!(std::abs(wind.direction_deg) <= 360))
    w.fail_key("direction_deg",
               "must lie within +-360 degrees (got " + format_number(wind.direction_deg) + ")");
  wind.air_density = w.get_positive("air_density", limits::air_density, wind.air_density);
  wind.working_half_width =
      w.get_positive("working_half_width", limits::height, wind.working_half_width);
  wind.vehicle_sway = w.get_nonnegative("vehicle_sway", limits::height, 0.0);
  wind.track_tolerance = w.get_nonnegative("track_tolerance", limits::height, 0.0);
  if (wind.turbulence.on && wind.speed == 0)
    w.fail_key("turbulence", "needs a mean wind (speed > 0): the drag is linearised about it");
  if (!(wind.permissible_m() > 0))
    w.fail("working_half_width - vehicle_sway - track_tolerance must be positive (got " +
           format_number(wind.permissible_m()) + " m)");
  return wind;
}

// 'conditions' (docs/conditions.md).
LineConditions read_conditions(const InputNode& c, const CatenaryMesh& mesh) {
  c.allow_only({"ice", "temperature_change_k", "wind"});
  LineConditions out;
  if (c.has("ice")) out.ice = read_ice(c["ice"], mesh);
  if (c.has("wind")) out.wind = read_wind(c["wind"]);
  out.temperature_change_k = c.get_double("temperature_change_k", 0.0);
  if (!(std::abs(out.temperature_change_k) <= kMaxTemperatureChange))
    c.fail_key("temperature_change_k", "must lie within +-100 K of the design temperature (got " +
                                           format_number(out.temperature_change_k) + " K)");
  return out;
}

void read_modal_settings(const InputNode& modal, ModalSettings& s) {
  modal.allow_only({"dropper_shapes", "contact_flexibility", "modes", "participation", "droppers",
                    "bars", "method", "exact_droppers_within"});
  const std::string method = modal.get_choice("method", {"auto", "whole", "window"}, "auto");
  s.method = method == "whole"    ? ModalSettings::Method::whole
             : method == "window" ? ModalSettings::Method::window
                                  : ModalSettings::Method::automatic;
  s.dropper_shapes = modal.get_bool("dropper_shapes", true);
  s.contact_flexibility = modal.get_bool("contact_flexibility", true);
  s.vertical_only = modal.get_choice("modes", {"all", "vertical"}, "all") == "vertical";
  s.participation = modal.get_positive("participation", s.participation);
  if (s.participation >= 1) modal.fail_key("participation", "must be below 1");
  s.dropper_check = modal.get_choice("droppers", {"bounded", "all"}, "bounded") == "all"
                        ? ModalSettings::DropperCheck::all
                        : ModalSettings::DropperCheck::bounded;
  const std::string bars =
      modal.get_choice("bars", {"slack", "slack_exact", "exact"}, "slack_exact");
  s.bars = bars == "exact"         ? ModalSettings::Bars::exact
           : bars == "slack_exact" ? ModalSettings::Bars::slack_exact
                                   : ModalSettings::Bars::slack;
  s.exact_droppers_within = modal.get_nonnegative("exact_droppers_within", limits::distance, 0.0);
  if (s.exact_droppers_within > 0 && s.bars == ModalSettings::Bars::exact)
    modal.fail_key("exact_droppers_within", "bars: exact already takes every bar's exact force");
}

}  // namespace

void read_catenary_model(const InputNode& section, CatenaryScene& out) {
  out.fidelity_given = section.has("model");
  const std::string model = section.get_choice("model", {"nonlinear", "linear", "modal"}, "linear");
  out.fidelity = model == "nonlinear" ? CatenaryFidelity::nonlinear
                 : model == "modal"   ? CatenaryFidelity::modal
                                      : CatenaryFidelity::linear;
  const bool modal = out.fidelity == CatenaryFidelity::modal;
  for (const char* key : {"max_frequency_hz", "modal"})
    if (section.has(key) && !modal) section.fail_key(key, "only for model: modal");
  if (section.has("max_frequency_hz")) {
    out.modal_cutoff_given = true;
    const InputNode f = section["max_frequency_hz"];
    if (f.is_scalar() && f.as_string() == "all")
      out.modal.max_frequency_hz = 0;  // every mode
    else
      out.modal.max_frequency_hz = section.get_positive("max_frequency_hz", limits::frequency);
  }
  if (section.has("modal")) read_modal_settings(section["modal"], out.modal);
}

CatenaryScene load_catenary_scene(const InputNode& scene, const MeshSizeCheck& size_check,
                                  const DesignBuilder& build) {
  check_scene_sections(scene);
  const InputNode section = scene["catenary"];
  section.allow_only({"design", "form_finding", "model", "max_frequency_hz", "modal"});
  CatenaryScene out;
  out.scene_file = scene.file();
  out.design_path = section.get_file_path("design");
  const InputNode design = section.load_referenced("design");
  try {
    out.mesh = build ? build(design, size_check) : build_catenary_design(design, size_check);
  } catch (const InputError& e) {
    design.rethrow_with_origin(e);
  }
  out.mesh.source_file = out.design_path;
  out.form_finding = section.get_bool("form_finding", out.mesh.form_finding_default);
  read_catenary_model(section, out);
  if (scene.has("conditions")) out.mesh.conditions = read_conditions(scene["conditions"], out.mesh);
  if (scene.has("elasticity")) out.elasticity = read_elasticity(scene["elasticity"], out.mesh);
  return out;
}

ModesSection load_modes_section(const InputNode& scene) {
  ModesSection r;
  if (!scene.has("modes")) return r;
  const InputNode m = scene["modes"];
  m.allow_only({"count", "max_frequency_hz"});
  r.count = static_cast<int>(m.get_int("count", 20));
  if (r.count < 1) m.fail_key("count", "must be at least 1");
  r.max_frequency_hz = m.get_positive("max_frequency_hz", limits::frequency, 0.0);
  return r;
}

std::vector<double> ElasticityRequest::stations() const {
  std::vector<double> x;
  const long n = static_cast<long>(std::floor((to_x - from_x) / step + 1e-9));
  for (long i = 0; i <= n; ++i) x.push_back(from_x + i * step);
  return x;
}

}  // namespace pcsim::scene
