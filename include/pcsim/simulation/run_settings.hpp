// The output settings of a run scene, shared by `pcsim run` and the runs of
// `pcsim study accuracy`.
#pragma once

#include <string>

#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace pcsim::simulation {

inline output::RunSettings run_settings(const scene::RunScene& run, const std::string& scene_name) {
  output::RunSettings s;
  s.scene_name = scene_name;
  s.speed = run.speed;
  s.analysis_from_x = run.analysis_from_x;
  s.analysis_to_x = run.analysis_to_x;
  s.analysis_from_span = run.analysis_from_span;
  s.analysis_to_span = run.analysis_to_span;
  s.cutoff_hz = run.cutoff_hz;
  s.loss_min_duration_s = run.loss_min_duration_s;
  s.dropper_forces = run.dropper_forces;
  const auto& wind = run.catenary.mesh.conditions.wind;
  if (wind.any()) s.permissible_lateral_m = wind.permissible_m();
  // The modal basis keeps the contact wire's lateral rows under a wind only.
  s.lateral_static = run.catenary.fidelity == catenary::CatenaryFidelity::modal && !wind.any();
  for (const auto& p : run.pantographs) {
    s.pantograph_names.push_back(p.name);
    s.cross_wind.push_back({p.cross_wind, p.cross_wind_force, p.head_lateral_offset});
  }
  s.assessment = run.assessment;
  return s;
}

}  // namespace pcsim::simulation
