// The keys of parametric designs that describe a real line (see
// docs/design-format.md): presag profiles, dropper positions per span,
// tension sections and overlaps, tensioning devices, support and steady-arm
// models, irregularities. Syntax here; ranges in the builder.
#include <fstream>
#include <sstream>

#include "design_reader_internal.hpp"

namespace pcsim::scene::reader {

using namespace pcsim::catenary;

namespace {

std::vector<long> read_ints(const InputNode& n, const char* what) {
  if (!n.is_sequence()) n.fail(std::string("must be a list of ") + what);
  std::vector<long> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(n.at(i).as_int());
  return out;
}

std::vector<double> read_list(const InputNode& n, const char* what) {
  if (!n.is_sequence()) n.fail(std::string("must be a list of ") + what);
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(n.at(i).as_double());
  return out;
}

MessengerSupportDesign read_messenger_support(const InputNode& n) {
  n.allow_only({"model", "stiffness", "mass"});
  MessengerSupportDesign s;
  const std::string model = n.get_choice("model", {"fixed", "spring", "spring_mass"}, "fixed");
  s.model = model == "spring"        ? MessengerSupportModel::spring
            : model == "spring_mass" ? MessengerSupportModel::spring_mass
                                     : MessengerSupportModel::fixed;
  // A key the model does not use is an error, as for steady_arms.
  if (s.model == MessengerSupportModel::fixed && n.has("stiffness"))
    n.fail_key("stiffness", "only for models 'spring' and 'spring_mass'");
  if (s.model != MessengerSupportModel::spring_mass && n.has("mass"))
    n.fail_key("mass", "only for model 'spring_mass'");
  if (s.model != MessengerSupportModel::fixed) s.stiffness = n.get_double("stiffness");
  if (s.model == MessengerSupportModel::spring_mass) s.mass = n.get_double("mass");
  return s;
}

SteadyArmDesign read_steady_arm(const InputNode& n) {
  n.allow_only({"model", "mass", "length", "axial_stiffness", "stiffness"});
  SteadyArmDesign a;
  const std::string model = n.get_choice("model", {"constraint", "hinged", "spring"}, "constraint");
  a.model = model == "hinged"   ? SteadyArmModel::hinged
            : model == "spring" ? SteadyArmModel::spring
                                : SteadyArmModel::constraint;
  a.mass = n.get_double("mass", 0.0);
  if (a.model != SteadyArmModel::hinged && (n.has("length") || n.has("axial_stiffness")))
    n.fail_key(n.has("length") ? "length" : "axial_stiffness", "only for model 'hinged'");
  if (a.model != SteadyArmModel::spring && n.has("stiffness"))
    n.fail_key("stiffness", "only for model 'spring' (a hinged arm has 'axial_stiffness')");
  if (a.model == SteadyArmModel::hinged) {
    a.length = n.get_double("length");
    a.axial_stiffness = n.get_double("axial_stiffness", a.axial_stiffness);
  }
  if (a.model == SteadyArmModel::spring) a.stiffness = n.get_double("stiffness");
  return a;
}

// Two numeric columns (x, dz) [m]; '#' starts a comment; a first line that
// is not numeric is a header.
void read_profile_file(const InputNode& n, IrregularityDesign& out) {
  const std::string path = n.resolve_path(n.as_string());
  std::ifstream in(path);
  if (!in) n.fail("cannot open the profile file '" + path + "'");
  std::string line;
  int number = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++number;
    line = line.substr(0, line.find('#'));
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t') c = ' ';
    std::istringstream s(line);
    double x, dz;
    std::string rest;
    if (!(s >> x)) {
      if (line.find_first_not_of(' ') == std::string::npos) continue;
      if (header_allowed) {
        header_allowed = false;
        continue;
      }
      n.fail("line " + std::to_string(number) + " of '" + path + "' is not two numbers (x, dz)");
    }
    if (!(s >> dz) || (s >> rest))
      n.fail("line " + std::to_string(number) + " of '" + path + "' is not two numbers (x, dz)");
    header_allowed = false;
    out.profile_x.push_back(x);
    out.profile_dz.push_back(dz);
  }
  if (out.profile_x.size() < 2)
    n.fail("'" + path + "' needs at least two (x, dz) points, it has " +
           std::to_string(out.profile_x.size()));
}

RandomIrregularity read_random(const InputNode& n) {
  n.allow_only({"rms", "wavelength_min", "wavelength_max", "spectrum", "exponent", "seed"});
  RandomIrregularity r;
  r.rms = n.get_double("rms");
  r.wavelength_min = n.get_double("wavelength_min", r.wavelength_min);
  r.wavelength_max = n.get_double("wavelength_max", r.wavelength_max);
  const std::string spectrum = n.get_choice("spectrum", {"uniform", "power_law"}, "uniform");
  r.spectrum =
      spectrum == "power_law" ? IrregularitySpectrum::power_law : IrregularitySpectrum::uniform;
  if (r.spectrum != IrregularitySpectrum::power_law && n.has("exponent"))
    n.fail_key("exponent", "only for spectrum 'power_law'");
  r.exponent = n.get_double("exponent", r.exponent);
  r.seed = n.get_int("seed", r.seed);
  return r;
}

}  // namespace

void read_presag(const InputNode& root, ParametricDesign& d) {
  if (!root.has("presag")) return;
  const InputNode p = root["presag"];
  if (!p.is_map()) {
    d.presag = p.as_double();
    return;
  }
  p.allow_only({"profile", "sag"});
  const std::string profile = p.get_choice("profile", {"parabola", "droppers", "heights"}, "");
  if (profile.empty())
    p.fail_key("profile", "required key is missing (parabola, droppers, heights)");
  d.presag_profile = profile == "droppers"  ? PresagProfile::droppers
                     : profile == "heights" ? PresagProfile::heights
                                            : PresagProfile::parabola;
  if (d.presag_profile == PresagProfile::heights) {
    if (p.has("sag")) p.fail_key("sag", "profile 'heights' takes its sags from droppers.sags");
  } else {
    d.presag = p.get_double("sag");
    d.presag_key = "presag.sag";
  }
}

std::vector<SpanDroppers> read_span_droppers(const InputNode& list) {
  if (!list.is_sequence()) list.fail("must be a list of {spans, positions, sags}");
  std::vector<SpanDroppers> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const InputNode n = list.at(i);
    n.allow_only({"spans", "positions", "sags"});
    SpanDroppers s;
    s.spans = read_ints(n["spans"], "span numbers (1-based)");
    s.positions = read_list(n["positions"], "distances from the span's first support [m]");
    if (n.has("sags")) s.sags = read_list(n["sags"], "sags [m]");
    out.push_back(std::move(s));
  }
  return out;
}

void read_line(const InputNode& root, ParametricDesign& d) {
  if (root.has("sections")) {
    const InputNode list = root["sections"];
    if (!list.is_sequence() || list.size() == 0) list.fail("must be a non-empty list of sections");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const InputNode s = list.at(i);
      s.allow_only({"spans", "radius"});
      d.sections.push_back({s.get_int("spans"), s.get_double("radius", 0.0)});
    }
  }
  if (root.has("overlap")) {
    const InputNode o = root["overlap"];
    o.allow_only({"spans", "raise", "anchor_raise", "separation"});
    d.overlap.spans = o.get_int("spans", d.overlap.spans);
    d.overlap.raise = o.get_double("raise", d.overlap.raise);
    d.overlap.anchor_raise = o.get_double("anchor_raise", 2.0 * d.overlap.raise);
    d.overlap.separation = o.get_double("separation", d.overlap.separation);
  }
  if (root.has("tensioning")) {
    const InputNode t = root["tensioning"];
    t.allow_only({"device", "ratio", "weight_mass", "stiffness", "travel"});
    const std::string device = t.get_choice("device", {"fixed", "weight", "spring"}, "fixed");
    d.tensioning.device = device == "weight"   ? TensioningDeviceKind::weight
                          : device == "spring" ? TensioningDeviceKind::spring
                                               : TensioningDeviceKind::fixed;
    if (device != "weight" && (t.has("ratio") || t.has("weight_mass")))
      t.fail_key(t.has("ratio") ? "ratio" : "weight_mass", "only for device 'weight'");
    if (device != "spring" && t.has("stiffness"))
      t.fail_key("stiffness", "only for device 'spring'");
    d.tensioning.ratio = t.get_double("ratio", 1.0);
    if (t.has("weight_mass")) d.tensioning.weight_mass = t.get_double("weight_mass");
    if (device == "spring") d.tensioning.stiffness = t.get_double("stiffness");
    if (device == "fixed" && t.has("travel")) t.fail_key("travel", "only for a device that moves");
    d.tensioning.travel = t.get_positive("travel", limits::distance, 0.0);
  }
}

void read_supports(const InputNode& root, ParametricDesign& d) {
  if (root.has("steady_arms")) d.steady_arms = read_steady_arm(root["steady_arms"]);
  if (root.has("messenger_supports"))
    d.messenger_supports = read_messenger_support(root["messenger_supports"]);
  if (!root.has("support_overrides")) return;
  const InputNode list = root["support_overrides"];
  if (!list.is_sequence())
    list.fail("must be a list of {supports, messenger_supports, steady_arms}");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const InputNode n = list.at(i);
    n.allow_only({"supports", "messenger_supports", "steady_arms"});
    SupportOverride o;
    o.supports = read_ints(n["supports"], "support numbers (0-based)");
    if (n.has("messenger_supports")) o.messenger = read_messenger_support(n["messenger_supports"]);
    if (n.has("steady_arms")) o.steady_arm = read_steady_arm(n["steady_arms"]);
    if (!o.messenger && !o.steady_arm) n.fail("must give messenger_supports or steady_arms");
    d.support_overrides.push_back(std::move(o));
  }
}

void read_irregularities(const InputNode& root, ParametricDesign& d) {
  if (!root.has("irregularities")) return;
  const InputNode ir = root["irregularities"];
  ir.allow_only({"profile", "random", "wear"});
  if (ir.has("profile")) read_profile_file(ir["profile"], d.irregularities);
  if (ir.has("random")) d.irregularities.random = read_random(ir["random"]);
  if (!ir.has("wear")) return;
  const InputNode wear = ir["wear"];
  if (!wear.is_sequence()) wear.fail("must be a list of {from, to, section_loss}");
  for (std::size_t i = 0; i < wear.size(); ++i) {
    const InputNode w = wear.at(i);
    w.allow_only({"from", "to", "section_loss"});
    d.irregularities.wear.push_back(
        {w.get_double("from"), w.get_double("to"), w.get_double("section_loss")});
  }
}

}  // namespace pcsim::scene::reader
