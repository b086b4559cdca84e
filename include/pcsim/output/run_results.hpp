// Results of a dynamic run (`pcsim run`): the EN 50318 statistics of every
// pantograph (contact force low-pass filtered, zero phase, over the analysis
// section; thesis 3.4), the uplift at the supports, results.h5 (time series),
// field snapshots (XDMF for ParaView) and summary.json. Called on rank 0.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/contact/records.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/statistics.hpp"

namespace pcsim::output {

// What the writer needs to know of the run.
struct RunSettings {
  std::string scene_name;
  double speed = 0;  // [m/s]
  double analysis_from_x = 0, analysis_to_x = 0;
  int analysis_from_span = 0, analysis_to_span = 0;  // 1-based
  double cutoff_hz = 20;
  bool dropper_forces = true;
  std::vector<std::string> pantograph_names;
};

// The recorded run (rank 0): one record per accepted step, and the node
// positions at the snapshot times.
struct RunHistory {
  std::vector<contact::StepRecord> steps;
  std::vector<double> snapshot_times;
  std::vector<std::vector<double>> snapshots;
};

struct PantographStatistics {
  std::string name;
  bool complete = false;  // crossed the whole analysis section
  ForceStatistics force;
};

struct RunStatistics {
  std::vector<PantographStatistics> pantographs;
  double max_uplift_m = 0;  // contact wire at the supports of the analysis section
};

// Zero-phase low-pass of a signal sampled at the accepted time steps; when
// the step size changed (rejected steps) the signal is interpolated linearly
// onto a uniform grid of the smallest step first.
std::vector<double> filter_uniformly_sampled(const std::vector<double>& time,
                                             const std::vector<double>& signal, double cutoff_hz);

// Statistics, results.h5 and the snapshot XDMF; static_node_values: the
// static configuration (6 per node).
RunStatistics write_run_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                const std::vector<double>& static_node_values,
                                const RunSettings& settings, const RunHistory& history);

// summary.json: the statistics plus the given performance and solver facts.
void write_run_summary(const OutputDir& out, const RunSettings& settings,
                       const RunStatistics& stats, const nlohmann::json& facts);

}  // namespace pcsim::output
