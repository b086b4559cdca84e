#include "pcsim/output/run_results.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "h5_series.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/mesh_xdmf.hpp"

namespace pcsim::output {

std::vector<double> filter_uniformly_sampled(const std::vector<double>& time,
                                             const std::vector<double>& signal, double cutoff_hz) {
  const std::size_t n = time.size();
  constexpr std::size_t kFilterExtension = 3 * (2 * 2 + 1);  // zero_phase_filter, order 4
  if (n <= kFilterExtension) return signal;
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

// Runs f on results.h5 opened for reading.
template <class F>
void with_results(const OutputDir& out, F f) {
  const std::string path = out.file("results.h5");
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw SolverError("cannot open " + path);
  try {
    f(file);
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
}

// Rows of a rows x cols dataset.
std::vector<std::vector<double>> read_rows(hid_t file, const std::string& path) {
  std::vector<hsize_t> dims;
  const auto values = h5::read(file, path, &dims);
  const std::size_t cols = dims.size() > 1 ? dims[1] : 1;
  std::vector<std::vector<double>> rows(dims.empty() ? 0 : dims[0]);
  for (std::size_t i = 0; i < rows.size(); ++i)
    rows[i].assign(values.begin() + i * cols, values.begin() + (i + 1) * cols);
  return rows;
}

// Largest uplift of the contact wire at the supports of the analysis section
// into stats, with its support (the first to reach it; none where no support rose).
void max_uplift(hid_t file, const catenary::CatenaryMesh& mesh, const RunSettings& s,
                RunStatistics& stats) {
  std::vector<hsize_t> dims;
  const auto uplift = h5::read(file, "/supports/uplift", &dims);
  const std::size_t ns = mesh.support_x.size();
  double largest = 0;
  for (std::size_t i = 0; i < uplift.size(); ++i) {
    const double xs = mesh.support_x[i % ns];
    if (xs >= s.analysis_from_x - kSupportTolerance && xs <= s.analysis_to_x + kSupportTolerance &&
        uplift[i] > largest) {
      largest = uplift[i];
      stats.max_uplift_x = xs;
    }
  }
  stats.max_uplift_m = largest;
}

// Pantograph p: its filtered contact force into results.h5, and its statistics.
PantographStatistics pantograph_results(hid_t file, const RunSettings& s,
                                        const std::vector<double>& time, std::size_t p) {
  const std::string g = "/pantographs/" + s.pantograph_names[p];
  const auto x = h5::read(file, g + "/position");
  const auto force = h5::read(file, g + "/contact_force");
  const auto filtered = filter_uniformly_sampled(time, force, s.cutoff_hz);
  h5::write(file, g + "/" + kContactForceFiltered, filtered, {filtered.size()}, "N",
            "contact force, zero-phase low-pass filtered (analysis cutoff)");
  PantographStatistics st;
  st.name = s.pantograph_names[p];
  // A run cut short (-ts_max_steps, -ts_max_time) has no complete section.
  st.complete = !x.empty() && x.front() <= s.analysis_from_x && x.back() >= s.analysis_to_x;
  if (st.complete)
    st.force = force_statistics(x, filtered, force, s.analysis_from_x, s.analysis_to_x);
  const bool cross_wind = p < s.cross_wind.size() && s.cross_wind[p].on;
  if (cross_wind) {
    h5::write(file, g + "/" + kCrossWindForce, {s.cross_wind[p].force_n}, {1}, "N",
              "the mean cross-wind's lateral force on the pantograph (towards +y)");
    h5::write(file, g + "/" + kHeadLateralOffset, {s.cross_wind[p].offset_m}, {1}, "m",
              "the head's quasi-static lateral deflection under that force (towards +y)");
  }
  if (st.complete && h5::exists(file, g + "/wire_lateral")) {
    const auto y = h5::read(file, g + "/wire_lateral");
    const double head = cross_wind ? s.cross_wind[p].offset_m : 0.0;
    for (std::size_t i = 0; i < y.size() && i < x.size(); ++i) {
      if (x[i] < s.analysis_from_x || x[i] > s.analysis_to_x) continue;
      if (std::abs(y[i]) > st.max_lateral_m)
        st.max_lateral_m = std::abs(y[i]), st.max_lateral_x = x[i];
      if (std::abs(y[i] - head) > st.max_on_head_m)
        st.max_on_head_m = std::abs(y[i] - head), st.max_on_head_x = x[i];
    }
  }
  st.judged_lateral_m = cross_wind ? st.max_on_head_m : st.max_lateral_m;
  if (st.complete && s.loss_min_duration_s > 0)
    st.force.loss_of_contact_percent = loss_of_contact_percent(
        x, time, force, s.analysis_from_x, s.analysis_to_x, s.loss_min_duration_s);
  return st;
}

}  // namespace

void write_static_mesh(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                       const std::vector<double>& static_values) {
  const auto static_positions = catenary::positions_from_node_values(static_values);
  write_mesh_h5_xdmf(mesh, static_positions, out.file("static_mesh.h5"), out.file("static.xdmf"),
                     {}, out.provenance());
}

void write_snapshots_view(const OutputDir& out, const catenary::CatenaryMesh& mesh) {
  std::vector<double> times;
  std::size_t pantographs = 0;
  with_results(out, [&](hid_t file) {
    if (h5::exists(file, "/snapshots/time")) times = h5::read(file, "/snapshots/time");
    std::vector<hsize_t> dims;
    if (h5::exists(file, "/snapshots/xdmf/pantograph_cells")) {
      h5::read(file, "/snapshots/xdmf/pantograph_cells", &dims);
      pantographs = dims.empty() ? 0 : dims[0];
    }
  });
  if (!times.empty())
    write_snapshots_xdmf(mesh, "static_mesh.h5", "results.h5", times, out.file("snapshots.xdmf"),
                         pantographs);
}

RunStatistics finish_run_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                 const RunSettings& s) {
  const std::string path = out.file("results.h5");
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) throw SolverError("cannot open " + path);
  const int fd = h5::descriptor(file);
  RunStatistics stats;
  try {
    const auto time = h5::read(file, "/time");
    max_uplift(file, mesh, s, stats);
    for (std::size_t p = 0; p < s.pantograph_names.size(); ++p)
      stats.pantographs.push_back(pantograph_results(file, s, time, p));
    errno = 0;
    try {
      h5::set_attribute(file, "/", "complete", 1.0);
    } catch (const std::exception& e) {
      throw OutputError(path, write_failure_reason(path, errno, e.what()));
    }
  } catch (...) {
    h5::discard_close(file, fd);
    throw;
  }
  errno = 0;
  if (H5Fclose(file) < 0) {
    const int saved = errno;
    h5::discard_close(file, fd);
    throw OutputError(path, write_failure_reason(path, saved, "HDF5 could not close it"));
  }
  write_snapshots_view(out, mesh);
  return stats;
}

std::vector<ContactHistory> read_contact_histories(const OutputDir& out, const RunSettings& s) {
  std::vector<ContactHistory> histories(s.pantograph_names.size());
  with_results(out, [&](hid_t file) {
    const auto time = h5::read(file, "/time");
    for (std::size_t p = 0; p < histories.size(); ++p) {
      const std::string g = "/pantographs/" + s.pantograph_names[p];
      histories[p].name = s.pantograph_names[p];
      histories[p].time = time;
      histories[p].x = h5::read(file, g + "/position");
      histories[p].force = h5::read(file, g + "/contact_force");
      histories[p].wire_force = read_rows(file, g + "/wire_force");
    }
  });
  return histories;
}

EnergyHistory read_energy_history(const OutputDir& out) {
  EnergyHistory h;
  with_results(out, [&](hid_t file) {
    h.time = h5::read(file, "/time");
    h.energy = h5::read(file, "/energy/energy");
    h.power_external = h5::read(file, "/energy/power_external");
    h.power_dissipative = h5::read(file, "/energy/power_dissipative");
  });
  return h;
}

void write_run_summary(const OutputDir& out, const RunSettings& s, const RunStatistics* stats,
                       const nlohmann::json& facts) {
  nlohmann::json summary = facts;
  summary["complete"] = stats != nullptr;
  summary["scene"] = s.scene_name;
  summary["speed_kmh"] = s.speed * 3.6;
  summary["analysis"] = {
      {"from_x", s.analysis_from_x}, {"to_x", s.analysis_to_x}, {"cutoff_hz", s.cutoff_hz}};
  if (stats) {
    summary["pantographs"] = nlohmann::json::array();
    for (const auto& p : stats->pantographs) {
      if (!p.complete) {
        summary["pantographs"].push_back({{"name", p.name}, {"complete", false}});
        continue;
      }
      nlohmann::json figures = force_statistics_json(p.force);
      figures["name"] = p.name;
      figures["lateral"] = {{"max_abs_m", p.max_lateral_m},
                            {"at_x_m", p.max_lateral_x},
                            {"static_only", s.lateral_static}};
      const std::size_t i = summary["pantographs"].size();
      const bool cross_wind = i < s.cross_wind.size() && s.cross_wind[i].on;
      if (cross_wind) {
        figures["lateral"]["cross_wind_force_n"] = s.cross_wind[i].force_n;
        figures["lateral"]["head_offset_m"] = s.cross_wind[i].offset_m;
        figures["lateral"]["max_abs_on_head_m"] = p.max_on_head_m;
        figures["lateral"]["on_head_at_x_m"] = p.max_on_head_x;
      }
      if (s.permissible_lateral_m > 0) {
        figures["lateral"]["permissible_m"] = s.permissible_lateral_m;
        figures["lateral"]["inside"] = p.judged_lateral_m <= s.permissible_lateral_m;
      }
      summary["pantographs"].push_back(figures);
    }
    summary["max_uplift_at_support_m"] = stats->max_uplift_m;
    summary["max_uplift_at_support_x_m"] = std::isnan(stats->max_uplift_x)
                                               ? nlohmann::json(nullptr)
                                               : nlohmann::json(stats->max_uplift_x);
  }
  const std::string path = out.file("summary.json"), tmp = path + ".tmp";
  errno = 0;
  {
    std::ofstream file(tmp);
    file << summary.dump(2) << "\n";
    file.close();
    if (!file) {
      const int saved = errno;
      std::remove(tmp.c_str());
      throw OutputError(path, write_failure_reason(path, saved));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    std::remove(tmp.c_str());
    throw OutputError(path, write_failure_reason(path, saved));
  }
}

}  // namespace pcsim::output
