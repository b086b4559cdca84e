#include "pcsim/output/run_results.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/mesh_xdmf.hpp"
#include "pcsim/output/provenance.hpp"

namespace pcsim::output {

std::vector<double> filter_uniformly_sampled(const std::vector<double>& time,
                                             const std::vector<double>& signal, double cutoff_hz) {
  const std::size_t n = time.size();
  if (n < 8) return signal;
  const double dt = (time.back() - time.front()) / (n - 1);
  bool uniform = true;
  for (std::size_t i = 1; i < n && uniform; ++i)
    uniform = std::abs(time[i] - time[i - 1] - dt) < 1e-6 * dt;
  if (uniform) return zero_phase_lowpass(signal, 1.0 / dt, cutoff_hz);
  double dt_min = dt;  // the smallest step sets the grid
  for (std::size_t i = 1; i < n; ++i) dt_min = std::min(dt_min, time[i] - time[i - 1]);
  const std::size_t m = static_cast<std::size_t>((time.back() - time.front()) / dt_min) + 1;
  std::vector<double> resampled(m);
  std::size_t j = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const double tk = time.front() + k * dt_min;
    while (j + 2 < n && time[j + 1] < tk) ++j;
    const double w = std::clamp((tk - time[j]) / (time[j + 1] - time[j]), 0.0, 1.0);
    resampled[k] = (1 - w) * signal[j] + w * signal[j + 1];
  }
  const auto filtered_grid = zero_phase_lowpass(resampled, 1.0 / dt_min, cutoff_hz);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k =
        std::min(m - 1, static_cast<std::size_t>(std::lround((time[i] - time.front()) / dt_min)));
    out[i] = filtered_grid[k];
  }
  return out;
}

namespace {

// Uplift of the contact wire at the supports (n x supports), relative to the
// static configuration, and its maximum over the analysis section.
std::vector<double> support_uplift(const catenary::CatenaryMesh& mesh,
                                   const std::vector<double>& static_values, const RunSettings& s,
                                   const RunHistory& h, double& max_uplift) {
  const std::size_t n = h.steps.size(), ns = mesh.support_nodes.size();
  std::vector<double> uplift(n * ns);
  max_uplift = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < ns; ++k) {
      const double u = h.steps[i].support_z[k] - static_values[6 * mesh.support_nodes[k] + 2];
      uplift[i * ns + k] = u;
      const double xs = mesh.support_x[k];
      if (xs >= s.analysis_from_x - 1e-9 && xs <= s.analysis_to_x + 1e-9)
        max_uplift = std::max(max_uplift, u);
    }
  return uplift;
}

void write_snapshots(const OutputDir& out, H5File& h5, const catenary::CatenaryMesh& mesh,
                     const std::vector<double>& static_values, const RunHistory& h) {
  // Static mesh + displacement snapshots: ParaView animation of the wires.
  const auto static_positions = catenary::positions_from_node_values(static_values);
  write_mesh_h5_xdmf(mesh, static_positions, out.file("static_mesh.h5"), out.file("static.xdmf"),
                     {}, out.provenance());
  for (std::size_t k = 0; k < h.snapshots.size(); ++k) {
    std::vector<double> d(h.snapshots[k]);
    for (std::size_t i = 0; i < d.size(); ++i) d[i] -= static_positions[i];
    h5.write("/snapshots/displacement_" + std::to_string(k), d, mesh.nodes.size(), 3);
  }
  h5.write("/snapshots/time", h.snapshot_times);
  write_snapshots_xdmf(mesh, "static_mesh.h5", "results.h5", h.snapshot_times,
                       out.file("snapshots.xdmf"));
}

// The pantograph's time series into results.h5 and its statistics.
PantographStatistics pantograph_results(H5File& h5, const RunSettings& s, const RunHistory& h,
                                        const std::vector<double>& time, std::size_t p) {
  const std::size_t n = h.steps.size();
  std::vector<double> force(n), x(n), zw(n);
  const std::size_t nq = h.steps.empty() ? 0 : h.steps[0].q[p].size();
  std::vector<double> q(n * nq);
  for (std::size_t i = 0; i < n; ++i) {
    force[i] = h.steps[i].contact_force[p];
    x[i] = h.steps[i].contact_x[p];
    zw[i] = h.steps[i].wire_z[p];
    std::copy(h.steps[i].q[p].begin(), h.steps[i].q[p].end(), q.begin() + i * nq);
  }
  const std::string g = "/pantographs/" + s.pantograph_names[p];
  h5.write(g + "/position", x);
  h5.write(g + "/contact_force", force);
  h5.write(g + "/wire_height", zw);
  h5.write(g + "/q", q, n, nq);
  const auto filtered = filter_uniformly_sampled(time, force, s.cutoff_hz);
  h5.write(g + "/contact_force_filtered", filtered);
  PantographStatistics st;
  st.name = s.pantograph_names[p];
  // A run cut short (-ts_max_steps, -ts_max_time) has no complete section.
  st.complete = !x.empty() && x.front() <= s.analysis_from_x && x.back() >= s.analysis_to_x;
  if (st.complete)
    st.force = force_statistics(x, filtered, force, s.analysis_from_x, s.analysis_to_x);
  return st;
}

}  // namespace

RunStatistics write_run_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                const std::vector<double>& static_values, const RunSettings& s,
                                const RunHistory& h) {
  RunStatistics stats;
  const std::size_t n = h.steps.size();
  std::vector<double> time(n);
  for (std::size_t i = 0; i < n; ++i) time[i] = h.steps[i].t;
  H5File h5(out.file("results.h5"));
  stamp_provenance(h5, out.provenance());
  h5.write("/time", time);
  h5.write("/supports/x", mesh.support_x);
  h5.write("/supports/uplift", support_uplift(mesh, static_values, s, h, stats.max_uplift_m), n,
           mesh.support_nodes.size());
  if (s.dropper_forces && n > 0 && !h.steps[0].dropper_force.empty()) {
    const std::size_t nd = h.steps[0].dropper_force.size();
    std::vector<double> forces(n * nd);
    for (std::size_t i = 0; i < n; ++i)
      std::copy(h.steps[i].dropper_force.begin(), h.steps[i].dropper_force.end(),
                forces.begin() + i * nd);
    h5.write("/droppers/force", forces, n, nd);
  }
  if (!h.snapshots.empty()) write_snapshots(out, h5, mesh, static_values, h);
  h5.attribute("/", "analysis_from_x", s.analysis_from_x);
  h5.attribute("/", "analysis_to_x", s.analysis_to_x);
  h5.attribute("/", "speed_m_s", s.speed);
  for (std::size_t p = 0; p < s.pantograph_names.size(); ++p)
    stats.pantographs.push_back(pantograph_results(h5, s, h, time, p));
  return stats;
}

void write_run_summary(const OutputDir& out, const RunSettings& s, const RunStatistics& stats,
                       const nlohmann::json& facts) {
  nlohmann::json summary = facts;
  summary["scene"] = s.scene_name;
  summary["speed_kmh"] = s.speed * 3.6;
  summary["analysis"] = {
      {"from_x", s.analysis_from_x}, {"to_x", s.analysis_to_x}, {"cutoff_hz", s.cutoff_hz}};
  summary["pantographs"] = nlohmann::json::array();
  for (const auto& p : stats.pantographs) {
    if (!p.complete) {
      summary["pantographs"].push_back({{"name", p.name}, {"complete", false}});
      continue;
    }
    const auto& st = p.force;
    summary["pantographs"].push_back({{"name", p.name},
                                      {"mean_N", st.mean},
                                      {"std_N", st.std_dev},
                                      {"stat_max_N", st.statistical_max},
                                      {"stat_min_N", st.statistical_min},
                                      {"max_N", st.actual_max},
                                      {"min_N", st.actual_min},
                                      {"loss_of_contact_percent", st.loss_of_contact_percent},
                                      {"samples", st.samples}});
  }
  summary["max_uplift_at_support_m"] = stats.max_uplift_m;
  std::ofstream(out.file("summary.json")) << summary.dump(2) << "\n";
}

}  // namespace pcsim::output
