#include "pcsim/output/catenary_results.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/mesh_xdmf.hpp"
#include "pcsim/output/provenance.hpp"

namespace pcsim::output {

using catenary::BarKind;

namespace {

nlohmann::json static_json(const catenary::CatenaryMesh& mesh, const catenary::StaticResult& r,
                           const CatenaryRunInfo& info, const nlohmann::json& provenance) {
  nlohmann::json j;
  j["scene"] = info.scene_name;
  j["design"] = mesh.source_file;
  j["dofs"] = info.dofs;
  j["ranks"] = info.ranks;
  j["form_finding"] = info.form_finding;
  j["snes_iterations"] = r.snes_iterations;
  j["snes_residual_history"] = r.residual_history;
  j["converged_reason"] = r.converged_reason;
  j["force_scale_N"] = r.force_scale;  // tolerances are fractions of it (solvers/statics.hpp)
  j["tangent_negative_eigenvalues"] = r.negative_eigenvalues;
  j["warnings"] = r.warnings;
  j["max_height_error_m"] = r.max_height_error_m;
  j["max_tension_error_rel"] = r.max_tension_error_rel;
  j["segment_tensions_N"] = r.segment_tensions;
  if (!r.registration_forces.empty()) j["steady_arm_pull_off_N"] = r.registration_forces;
  for (const auto& d : mesh.tensioning_devices)
    j["tensioning_devices"].push_back(
        {{"wire", mesh.wires[d.wire].name},
         {"device", d.kind == catenary::TensioningKind::weight ? "weight" : "spring"},
         {"pull_N", d.pull},
         {"mass_kg", d.mass},
         {"stiffness_N_m", d.stiffness}});
  if (!r.blow_off.empty()) {
    const auto& b = r.blow_off;
    j["blow_off"] = {{"max_excursion_m", b.max_excursion_m},
                     {"max_excursion_x_m", b.max_excursion_x},
                     {"permissible_m", b.permissible_m},
                     {"margin_m", b.permissible_m - b.max_excursion_m},
                     {"inside", b.max_excursion_m <= b.permissible_m}};
  }
  j["wall_time_s"] = r.wall_time_s;
  j["provenance"] = provenance;
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
}

// The contact wires' lateral positions under wind (docs/conditions.md).
void write_blow_off(H5File& h5, const catenary::BlowOff& b) {
  h5.write("/blow_off/x", b.x, {"m", "station of each support and mid-span"});
  h5.write_int("/blow_off/at_support", std::vector<long>(b.at_support.begin(), b.at_support.end()),
               {"1", "1: a support, 0: a mid-span"});
  h5.write_int("/blow_off/wire", std::vector<long>(b.wire.begin(), b.wire.end()),
               {"1", "contact wire (0-based, in the order of their first station)"});
  h5.write("/blow_off/lateral", b.lateral,
           {"m",
            "contact wire's lateral position from the track centre line under the wind "
            "(+ to the left of the track)"});
  h5.write("/blow_off/lateral_bare", b.lateral_bare,
           {"m", "the same before the conditions (the bare line)"});
  h5.write("/blow_off/max_excursion", std::vector<double>{b.max_excursion_m},
           {"m", "largest |lateral position| at any node of a contact wire"});
  h5.write("/blow_off/permissible", std::vector<double>{b.permissible_m},
           {"m", "working half width - vehicle sway - track tolerance"});
}

void write_static_h5(const std::string& path, const catenary::CatenaryMesh& mesh,
                     const catenary::StaticResult& r, const nlohmann::json& provenance) {
  H5File h5(path);
  stamp_provenance(h5, provenance);
  h5.write("/nodes/values", r.node_values, mesh.nodes.size(), 6,
           {"m, 1",
            "static configuration: position (x, y, z) [m] and slope (dx, dy, dz) [1]",
            {"x", "y", "z", "dx", "dy", "dz"}});
  h5.write("/newton/residual_norm", r.residual_history,
           {"N", "residual 2-norm at each Newton iteration of the static solve"});
  std::vector<double> x, unstressed, force, length;
  std::vector<long> span, index;
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    const auto& bar = mesh.bars[b];
    if (bar.kind != BarKind::dropper) continue;
    x.push_back(r.node_values[6 * bar.nodes[0]]);
    span.push_back(bar.span);
    index.push_back(bar.index_in_span);
    unstressed.push_back(bar.unstressed_length);
    force.push_back(r.bar_forces[b]);
    length.push_back(r.bar_lengths[b]);
  }
  h5.write("/droppers/x", x, {"m", "x of the dropper's upper node"});
  h5.write_int("/droppers/span", span, {"1", "span of the dropper (0-based)"});
  h5.write_int("/droppers/index_in_span", index, {"1", "index of the dropper in its span"});
  h5.write("/droppers/unstressed_length", unstressed, {"m", "unstressed length (form-finding)"});
  h5.write("/droppers/length", length, {"m", "length in the static configuration"});
  h5.write("/droppers/force", force, {"N", "static axial force, tension positive"});
  h5.write("/wires/segment_tension", r.segment_tensions,
           {"N", "tension of each tension segment of the wires"});
  std::vector<double> target_z, target_design;
  for (std::size_t k = 0; k < mesh.height_targets.size(); ++k) {
    target_design.push_back(mesh.height_targets[k].z);
    target_z.push_back(r.target_heights[k]);
  }
  h5.write("/targets/design_z", target_design, {"m", "height targets of form-finding (design)"});
  h5.write("/targets/static_z", target_z, {"m", "heights reached at the targets"});
  if (!r.registration_forces.empty()) {
    std::vector<long> support;
    std::vector<double> station;
    for (const auto& reg : mesh.registrations) {
      support.push_back(reg.support);
      station.push_back(mesh.support_x[reg.support]);
    }
    h5.write_int("/steady_arms/support", support, {"1", "support index of each steady arm"});
    h5.write("/steady_arms/x", station, {"m", "station of each steady arm's support"});
    h5.write("/steady_arms/pull_off_force", r.registration_forces,
             {"N", "steady-arm pull-off force at the static configuration"});
  }
  if (!r.blow_off.empty()) write_blow_off(h5, r.blow_off);
  h5.attribute("/", "max_height_error_m", r.max_height_error_m);
  h5.attribute("/", "max_tension_error_rel", r.max_tension_error_rel);
}

}  // namespace

void write_static_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                          const catenary::StaticResult& r, const CatenaryRunInfo& info) {
  write_static_h5(out.file("static.h5"), mesh, r, out.provenance());
  write_mesh_h5_xdmf(mesh, catenary::positions_from_node_values(r.node_values),
                     out.file("static_mesh.h5"), out.file("static.xdmf"), {}, out.provenance());
  write_json(out.file("summary.json"), static_json(mesh, r, info, out.provenance()));
}

void write_elasticity(const OutputDir& out, const catenary::ElasticityResult& r) {
  std::ofstream f(out.file("elasticity.csv"));
  f << "# static uplift of the lowest contact wire under an upward force of " << r.force
    << " N\n# x_m,uplift_mm_per_100N,uplift_m,contact_wire\n";
  f.precision(10);
  for (std::size_t i = 0; i < r.x.size(); ++i)
    f << r.x[i] << "," << 1e3 * r.uplift[i] * 100.0 / r.force << "," << r.uplift[i] << ","
      << r.wire[i] << "\n";
}

std::vector<long> modes_vertical(const catenary::CatenaryMesh& mesh,
                                 const std::vector<std::vector<double>>& shapes) {
  std::vector<int> nodes;
  for (const auto& w : mesh.wires)
    if (w.kind == catenary::WireKind::contact)
      nodes.insert(nodes.end(), w.nodes.begin(), w.nodes.end());
  if (nodes.empty())
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) nodes.push_back(static_cast<int>(i));
  std::vector<long> vertical;
  for (const auto& shape : shapes) {
    double y2 = 0, z2 = 0;
    for (int i : nodes) {
      if (3 * static_cast<std::size_t>(i) + 2 >= shape.size()) continue;
      y2 += shape[3 * i + 1] * shape[3 * i + 1];
      z2 += shape[3 * i + 2] * shape[3 * i + 2];
    }
    vertical.push_back(z2 >= y2 ? 1 : 0);
  }
  return vertical;
}

void write_modes_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                         const catenary::StaticResult& statics, const catenary::ModesResult& modes,
                         const CatenaryRunInfo& info) {
  write_static_h5(out.file("static.h5"), mesh, statics, out.provenance());
  const auto positions = catenary::positions_from_node_values(statics.node_values);
  write_mesh_h5_xdmf(mesh, positions, out.file("static_mesh.h5"), out.file("static.xdmf"), {},
                     out.provenance());
  const auto vertical = modes_vertical(mesh, modes.shapes);
  {
    H5File h5(out.file("modes.h5"));
    stamp_provenance(h5, out.provenance());
    h5.write("/frequencies_hz", modes.frequencies_hz,
             {"Hz", "natural frequencies of the catenary about the static configuration"});
    h5.write("/geometry", positions, mesh.nodes.size(), 3,
             {"m", "node positions of the static configuration"});
    h5.write_int("/vertical", vertical,
                 {"1",
                  "1: vertical mode, 0: lateral (which of z and y dominates the contact "
                  "wires' motion: sum of z^2 >= sum of y^2 over their nodes)"});
    std::vector<std::string> direction;
    for (long v : vertical) direction.push_back(v ? "vertical" : "lateral");
    h5.write_strings("/direction", direction, {"none", "'vertical' or 'lateral' (/vertical)"});
    for (std::size_t m = 0; m < modes.shapes.size(); ++m)
      h5.write("/shapes/mode_" + std::to_string(m), modes.shapes[m], mesh.nodes.size(), 3,
               {"kg^-1/2", "mode shape " + std::to_string(m) +
                               ": x, y, z of each node, mass-normalised (phi^T M phi = 1)"});
  }
  write_modes_xdmf(mesh, "modes.h5", "static_mesh.h5", modes.frequencies_hz, out.file("modes.xdmf"),
                   vertical);
  nlohmann::json j = static_json(mesh, statics, info, out.provenance());
  j["catenary_frequencies_hz"] = modes.frequencies_hz;
  j["catenary_mode_vertical"] = vertical;
  j["modes_converged"] = modes.converged;
  j["modes_max_relative_residual"] = modes.max_relative_residual;
  j["modes_wall_time_s"] = modes.wall_time_s;
  write_json(out.file("summary.json"), j);
}

}  // namespace pcsim::output
