#include "catenary_output.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "exit_status.hpp"
#include "pcsim/catenary/mesh_io.hpp"
#include "pcsim/output/h5_file.hpp"

namespace pcsim::app {

using catenary::BarKind;

namespace {

nlohmann::json static_json(const CommandContext& ctx, const assembly::CatenarySystem& system,
                           const catenary::StaticResult& r, const std::string& scene_name) {
  nlohmann::json j;
  j["scene"] = scene_name;
  j["design"] = system.mesh().source_file;
  j["dofs"] = system.layout().catenary_dofs();
  j["ranks"] = ctx.size;
  j["form_finding"] = system.layout().extra_dofs() > 0;
  j["snes_iterations"] = r.snes_iterations;
  j["snes_residual_history"] = r.residual_history;
  j["max_height_error_m"] = r.max_height_error_m;
  j["max_tension_error_rel"] = r.max_tension_error_rel;
  j["segment_tensions_N"] = r.segment_tensions;
  j["wall_time_s"] = r.wall_time_s;
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
}

void write_static_h5(const std::string& path, const catenary::CatenaryMesh& mesh,
                     const catenary::StaticResult& r) {
  H5File h5(path);
  h5.write("/nodes/values", r.node_values, mesh.nodes.size(), 6);
  h5.write("/newton/residual_norm", r.residual_history);
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
  h5.write("/droppers/x", x);
  h5.write_int("/droppers/span", span);
  h5.write_int("/droppers/index_in_span", index);
  h5.write("/droppers/unstressed_length", unstressed);
  h5.write("/droppers/length", length);
  h5.write("/droppers/force", force);
  h5.write("/wires/segment_tension", r.segment_tensions);
  std::vector<double> target_z, target_design;
  for (std::size_t k = 0; k < mesh.height_targets.size(); ++k) {
    target_design.push_back(mesh.height_targets[k].z);
    target_z.push_back(r.target_heights[k]);
  }
  h5.write("/targets/design_z", target_design);
  h5.write("/targets/static_z", target_z);
  h5.attribute("/", "max_height_error_m", r.max_height_error_m);
  h5.attribute("/", "max_tension_error_rel", r.max_tension_error_rel);
}

}  // namespace

void print_static_summary(const CommandContext& ctx, const assembly::CatenarySystem& system,
                          const catenary::StaticResult& r) {
  print0(ctx, "  Newton: %d iterations (%s), ||R||:", r.snes_iterations,
         r.converged_reason.c_str());
  for (double v : r.residual_history) print0(ctx, " %.2e", v);
  print0(ctx, "\n");
  if (!system.mesh().height_targets.empty())
    print0(ctx, "  max contact-wire height error at droppers: %.3e m\n", r.max_height_error_m);
  if (!system.mesh().tension_segments.empty())
    print0(ctx, "  max wire tension error: %.3e (relative)\n", r.max_tension_error_rel);
  double fmin = 1e300, fmax = -1e300;
  int n_droppers = 0;
  for (std::size_t b = 0; b < system.mesh().bars.size(); ++b)
    if (system.mesh().bars[b].kind == BarKind::dropper) {
      fmin = std::min(fmin, r.bar_forces[b]);
      fmax = std::max(fmax, r.bar_forces[b]);
      ++n_droppers;
    }
  if (n_droppers > 0)
    print0(ctx, "  %d droppers, static force %.1f .. %.1f N\n", n_droppers, fmin, fmax);
  print0(ctx, "  wall time %.3f s\n", r.wall_time_s);
}

void write_static_results(const CommandContext& ctx, const OutputDir& out,
                          const assembly::CatenarySystem& system, const catenary::StaticResult& r,
                          const std::string& scene_name) {
  on_rank0(ctx, [&] {
    const auto& mesh = system.mesh();
    write_static_h5(out.file("static.h5"), mesh, r);
    catenary::write_mesh_h5_xdmf(mesh, catenary::positions_from_node_values(r.node_values),
                                 out.file("static_mesh.h5"), out.file("static.xdmf"));
    write_json(out.file("summary.json"), static_json(ctx, system, r, scene_name));
  });
}

void write_modes_results(const CommandContext& ctx, const OutputDir& out,
                         const assembly::CatenarySystem& system,
                         const catenary::StaticResult& statics, const catenary::ModesResult& modes,
                         const std::string& scene_name) {
  on_rank0(ctx, [&] {
    const auto& mesh = system.mesh();
    write_static_h5(out.file("static.h5"), mesh, statics);
    const auto positions = catenary::positions_from_node_values(statics.node_values);
    catenary::write_mesh_h5_xdmf(mesh, positions, out.file("static_mesh.h5"),
                                 out.file("static.xdmf"));
    {
      H5File h5(out.file("modes.h5"));
      h5.write("/frequencies_hz", modes.frequencies_hz);
      h5.write("/geometry", positions, mesh.nodes.size(), 3);
      for (std::size_t m = 0; m < modes.shapes.size(); ++m)
        h5.write("/shapes/mode_" + std::to_string(m), modes.shapes[m], mesh.nodes.size(), 3);
    }
    catenary::write_modes_xdmf(mesh, "modes.h5", "static_mesh.h5", modes.frequencies_hz,
                               out.file("modes.xdmf"));
    nlohmann::json j = static_json(ctx, system, statics, scene_name);
    j["catenary_frequencies_hz"] = modes.frequencies_hz;
    j["modes_converged"] = modes.converged;
    j["modes_max_relative_residual"] = modes.max_relative_residual;
    j["modes_wall_time_s"] = modes.wall_time_s;
    write_json(out.file("summary.json"), j);
  });
}

}  // namespace pcsim::app
