// Results of a dynamic run (`pcsim run`): the EN 50318 statistics of every
// pantograph (contact force low-pass filtered, zero phase, over the analysis
// section; thesis 3.4), the uplift at the supports, read back from results.h5
// (streamed during the run: run_stream.hpp), field snapshots (XDMF for
// ParaView) and summary.json. Called on rank 0.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/contact/records.hpp"
#include "pcsim/core/criteria.hpp"
#include "pcsim/output/energy_results.hpp"
#include "pcsim/output/line_results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/statistics.hpp"

namespace pcsim::output {

// A pantograph's datasets that the end of a run adds beside its series (a
// restart's copy of results.h5 drops them: RunStream).
inline constexpr const char* kContactForceFiltered = "contact_force_filtered";
inline constexpr const char* kCrossWindForce = "cross_wind_force";
inline constexpr const char* kHeadLateralOffset = "head_lateral_offset";

// What the writer needs to know of the run.
struct RunSettings {
  std::string scene_name;
  double speed = 0;  // [m/s]
  double analysis_from_x = 0, analysis_to_x = 0;
  int analysis_from_span = 0, analysis_to_span = 0;  // 1-based
  double cutoff_hz = 20;
  double loss_min_duration_s = 0;  // a loss of contact counts from this duration on
  bool dropper_forces = true;
  // With a wind (conditions.wind): the contact point's lateral position is
  // judged against this (working half width - sway - tolerance) [m].
  double permissible_lateral_m = 0;
  bool lateral_static = false;  // the modal level in still air: the static lateral position
  std::vector<std::string> pantograph_names;
  // Per pantograph: the mean cross-wind's force [N] and the head's lateral
  // deflection [m] (pantographs[].cross_wind); not given: no entry is 'on'.
  struct HeadCrossWind {
    bool on = false;
    double force_n = 0, offset_m = 0;
  };
  std::vector<HeadCrossWind> cross_wind;
  Assessment assessment;  // the criteria set the figures are judged against
};

struct PantographStatistics {
  std::string name;
  bool complete = false;  // crossed the whole analysis section
  ForceStatistics force;
  // The contact point's largest |lateral position| over the analysis section
  // (the wire's y at the contact point) and its station [m].
  double max_lateral_m = 0, max_lateral_x = 0;
  // With a cross-wind on the pantograph: the same from the head's centre,
  // |y - head deflection| (its largest value and station) [m].
  double max_on_head_m = 0, max_on_head_x = 0;
  // What the permissible position is judged against: the former, or the
  // latter where the cross-wind blows the head aside too [m].
  double judged_lateral_m = 0;
};

// A support lies in the analysis section (or in a stretch of it) within this
// of its ends [m]: a support's x and a section's end may come from different
// sums of span lengths.
constexpr double kSupportTolerance = 1e-9;

struct RunStatistics {
  std::vector<PantographStatistics> pantographs;
  double max_uplift_m = 0;  // contact wire at the supports of the analysis section
  // The support of that largest uplift [m]; NaN where no support rose.
  double max_uplift_x = std::numeric_limits<double>::quiet_NaN();
};

// Zero-phase low-pass of a signal sampled at the accepted time steps; when
// the step size changed (rejected steps) the signal is interpolated linearly
// onto a uniform grid of the smallest step first. A record of at most 15
// samples (the order-4 filter's odd extension) is returned unfiltered: such a
// run is far too short for statistics (e.g. `-ts_max_steps 10`).
std::vector<double> filter_uniformly_sampled(const std::vector<double>& time,
                                             const std::vector<double>& signal, double cutoff_hz);

// The static configuration as a mesh file for the snapshots (static_mesh.h5,
// static.xdmf); static_node_values: 6 per node.
void write_static_mesh(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                       const std::vector<double>& static_node_values);
// snapshots.xdmf for the snapshots in results.h5 so far (none: no file).
void write_snapshots_view(const OutputDir& out, const catenary::CatenaryMesh& mesh);

// The end of a complete run, results.h5 closed by its stream: reads the time
// series back, adds every pantograph's contact_force_filtered, marks the file
// complete = 1, writes the snapshots' XDMF; returns the statistics.
RunStatistics finish_run_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                 const RunSettings& settings);

// The histories streamed into results.h5 that the line and energy results
// take (line_results.hpp, energy_results.hpp): every pantograph's time,
// station, head force and force on each contact wire (RunLayout::
// contact_wires), and E(t) with the powers (RunLayout::energy).
std::vector<ContactHistory> read_contact_histories(const OutputDir& out, const RunSettings& s);
EnergyHistory read_energy_history(const OutputDir& out);

// summary.json: the statistics (complete runs) plus the given performance and
// solver facts; an interrupted run writes "complete": false and no statistics.
void write_run_summary(const OutputDir& out, const RunSettings& settings,
                       const RunStatistics* stats, const nlohmann::json& facts);

}  // namespace pcsim::output
