#include "pcsim/output/run_stream.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>

#include "h5_series.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/provenance.hpp"

namespace pcsim::output {

namespace {

// The XDMF's views of snapshot k (write_snapshots_xdmf, mesh_xdmf.hpp): row k
// of /snapshots/<name>.
const char* const kSnapshotViews[] = {"displacement", "pantograph_points", "contact_force"};

std::string snapshot_view(const std::string& name, std::size_t k) {
  return "/snapshots/xdmf/" + name + "_" + std::to_string(k);
}

// The pantographs' grid of snapshots.xdmf: head p is point 2p, its contact
// point 2p + 1, one line between them; their displacement is zero (the points
// are where they are at the snapshot, Warp By Vector leaves them there).
void write_pantograph_grid(H5File& h5, std::size_t np) {
  if (np == 0) return;
  std::vector<long> cells;
  for (std::size_t p = 0; p < np; ++p)
    cells.insert(cells.end(), {static_cast<long>(2 * p), static_cast<long>(2 * p + 1)});
  h5.write_int("/snapshots/xdmf/pantograph_cells", cells, np, 2,
               {"1",
                "points of each pantograph's line in /snapshots/pantograph_points: head, "
                "contact point"});
  h5.write("/snapshots/xdmf/pantograph_displacement", std::vector<double>(6 * np, 0.0), 2 * np, 3,
           {"m",
            "zero: the pantograph points are at their positions of the snapshot (the "
            "node field every grid of snapshots.xdmf has)"});
}

// y of the contact wire at (x, z): on the element over x whose height there
// is closest to z; 0 if no element is over x.
double contact_y(const std::vector<std::array<int, 2>>& segments,
                 const std::vector<double>& positions, double x, double z) {
  double y = 0, best = HUGE_VAL;
  for (const auto& [a, b] : segments) {
    const double* pa = &positions[3 * static_cast<std::size_t>(a)];
    const double* pb = &positions[3 * static_cast<std::size_t>(b)];
    if (x < std::min(pa[0], pb[0]) || x > std::max(pa[0], pb[0])) continue;
    const double w = pb[0] != pa[0] ? (x - pa[0]) / (pb[0] - pa[0]) : 0.0;
    const double zs = pa[2] + w * (pb[2] - pa[2]);
    if (std::abs(zs - z) < best) best = std::abs(zs - z), y = pa[1] + w * (pb[1] - pa[1]);
  }
  return y;
}

double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

struct RunStream::Column {
  std::string path, unit, description;
  std::vector<hsize_t> row_shape;
  ColumnTake take;
  std::unique_ptr<h5::Series> series;
  std::vector<double> pending;
};

RunStream::RunStream(const std::string& path, const RunSettings& settings, RunLayout layout,
                     const nlohmann::json& provenance)
    : path_(path), layout_(std::move(layout)) {
  guarded([&] { create(settings, provenance); });
}

void RunStream::create(const RunSettings& settings, const nlohmann::json& provenance) {
  {
    H5File h5(path_);
    stamp_provenance(h5, provenance);
    if (layout_.snapshots) write_pantograph_grid(h5, settings.pantograph_names.size());
    h5.close();
  }
  file_ = H5Fopen(path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file_ < 0) throw SolverError("cannot open HDF5 file " + path_);
  fd_ = h5::descriptor(file_);
  open_series(true, settings);
  h5::write(file_, "/supports/x", layout_.support_x, {layout_.support_x.size()}, "m",
            "position of every support along the track");
  stamp(settings);
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw SolverError("cannot flush " + path_);
  last_flush_ = wall_seconds();
}

void RunStream::guarded(const std::function<void()>& write) {
  errno = 0;
  try {
    write();
  } catch (const OutputError&) {
    abandon();
    throw;
  } catch (const std::exception& e) {
    const int saved = errno;
    abandon();
    throw OutputError(path_, write_failure_reason(path_, saved, e.what()));
  }
}

void RunStream::abandon() {
  if (file_ >= 0) h5::discard_writes(file_, fd_);  // before the datasets close
  for (auto& c : columns_) c->pending.clear();
  buffered_ = 0;
  columns_.clear();
  snapshot_series_.clear();
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

RunStream::RunStream(const std::string& path, const RunSettings& settings, RunLayout layout,
                     std::size_t records, std::size_t snapshots, const nlohmann::json& provenance)
    : path_(path), layout_(std::move(layout)) {
  {
    H5File h5(path, H5File::Mode::append);
    stamp_provenance(h5, provenance);
  }
  H5E_BEGIN_TRY {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (file_ < 0) throw SolverError("cannot open HDF5 file " + path);
  fd_ = h5::descriptor(file_);
  try {
    open_series(false, settings);
    reopen(path, records, snapshots);
    h5::set_attribute(file_, "/", "complete", 0.0);
  } catch (...) {
    H5Fclose(file_);
    file_ = -1;
    throw;
  }
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
  last_flush_ = wall_seconds();
}

RunStream::~RunStream() {
  try {
    close();
  } catch (...) {  // a destructor does not throw; close() reports when called
  }
}

// One per-step dataset: created (or opened, for a restart) and checked to
// hold rows of the given shape.
void RunStream::add_column(bool create, const std::string& path, std::vector<hsize_t> shape,
                           const std::string& unit, const std::string& description,
                           ColumnTake take) {
  auto c = std::make_unique<Column>();
  c->path = path;
  c->series = create ? std::make_unique<h5::Series>(file_, path, shape, unit, description)
                     : std::make_unique<h5::Series>(file_, path);
  std::size_t row = 1;
  for (hsize_t d : shape) row *= d;
  if (c->series->row_size() != row)
    throw SolverError("results.h5: " + path + " has " + std::to_string(c->series->row_size()) +
                      " values per step, this run " + std::to_string(row));
  c->take = std::move(take);
  columns_.push_back(std::move(c));
}

// The per-step datasets in the order of a record's fields, and the
// snapshots' (docs/results-format.md).
void RunStream::open_series(bool create, const RunSettings& s) {
  const std::size_t ns = layout_.support_x.size();
  add_column(create, "/time", {}, "s", "time of every accepted step",
             [](const auto& r, const auto&, auto& out) { out.push_back(r.t); });
  for (std::size_t p = 0; p < s.pantograph_names.size(); ++p)
    open_pantograph_series(create, s.pantograph_names[p], p);
  add_column(create, "/supports/uplift", {ns}, "m",
             "contact-wire height at every support minus the static one",
             [this](const auto& r, const auto&, auto& out) {
               for (std::size_t k = 0; k < r.support_z.size(); ++k)
                 out.push_back(r.support_z[k] - layout_.support_static_z[k]);
             });
  if (layout_.droppers > 0)
    add_column(create, "/droppers/force", {layout_.droppers}, "N",
               "axial force of every dropper (mesh order)",
               [](const auto& r, const auto&, auto& out) {
                 out.insert(out.end(), r.dropper_force.begin(), r.dropper_force.end());
               });
  if (layout_.energy) {
    const std::tuple<const char*, const char*, const char*, double EnergySample::*> sets[] = {
        {"/energy/energy", "J", "energy of the system E(t)", &EnergySample::energy},
        {"/energy/power_external", "W", "power of the prescribed forces",
         &EnergySample::power_external},
        {"/energy/power_dissipative", "W", "power of the dissipative forces, <= 0",
         &EnergySample::power_dissipative}};
    for (const auto& [path, unit, description, member] : sets)
      add_column(
          create, path, {}, unit, description,
          [member = member](const auto&, const auto& e, auto& out) { out.push_back(e.*member); });
  }
  if (layout_.snapshots) open_snapshot_series(create, s.pantograph_names.size());
}

void RunStream::open_pantograph_series(bool create, const std::string& name, std::size_t p) {
  const std::string g = "/pantographs/" + name;
  add_column(create, g + "/position", {}, "m", "contact point along the track",
             [p](const auto& r, const auto&, auto& out) { out.push_back(r.contact_x[p]); });
  add_column(create, g + "/contact_force", {}, "N", "penalty contact force",
             [p](const auto& r, const auto&, auto& out) { out.push_back(r.contact_force[p]); });
  add_column(create, g + "/wire_height", {}, "m", "contact-wire height at the contact point",
             [p](const auto& r, const auto&, auto& out) { out.push_back(r.wire_z[p]); });
  add_column(create, g + "/wire_lateral", {}, "m",
             "lateral position of that contact wire at the contact point from the track centre "
             "line (+y; the modal level: its static position)",
             [p](const auto& r, const auto&, auto& out) {
               out.push_back(p < r.wire_y.size() ? r.wire_y[p] : 0.0);
             });
  add_column(create, g + "/q", {layout_.q_sizes[p]}, "m or rad",
             "generalised coordinates of the pantograph model (attribute labels)",
             [p](const auto& r, const auto&, auto& out) {
               out.insert(out.end(), r.q[p].begin(), r.q[p].end());
             });
  if (create && p < layout_.q_labels.size()) {
    std::string labels;
    for (const auto& label : layout_.q_labels[p]) labels += (labels.empty() ? "" : ",") + label;
    h5::set_attribute(file_, g + "/q", "labels", labels);
  }
  const std::size_t nw = layout_.contact_wires;
  if (nw > 0)
    add_column(create, g + "/wire_force", {nw}, "N", "contact force on each contact wire",
               [p, nw](const auto& r, const auto&, auto& out) {
                 for (std::size_t w = 0; w < nw; ++w)
                   out.push_back(p < r.wire_force.size() && w < r.wire_force[p].size()
                                     ? r.wire_force[p][w]
                                     : 0.0);
               });
}

void RunStream::open_snapshot_series(bool create, std::size_t np) {
  const hsize_t n = layout_.static_positions.size() / 3;
  const std::tuple<const char*, std::vector<hsize_t>, const char*, const char*> snapshot_sets[] = {
      {"/snapshots/time", {}, "s", "time of every snapshot"},
      {"/snapshots/displacement", {n, 3}, "m", "node displacement from the static configuration"},
      {"/snapshots/pantograph_position", {np}, "m", "contact point of every pantograph"},
      {"/snapshots/contact_force", {np}, "N", "contact force of every pantograph"},
      {"/snapshots/wire_height", {np}, "m", "contact-wire height at every contact point"},
      {"/snapshots/pantograph_points",
       {2 * np, 3},
       "m",
       "every pantograph's head (row 2p) and contact point (row 2p + 1): x, y, z"}};
  for (const auto& [path, shape, unit, description] : snapshot_sets)
    snapshot_series_.push_back(
        create ? std::make_unique<h5::Series>(file_, path, shape, unit, description)
               : std::make_unique<h5::Series>(file_, path));
}

// Cuts every series back to the checkpoint's counts.
void RunStream::reopen(const std::string& path, std::size_t records, std::size_t snapshots) {
  for (auto& c : columns_) {
    if (c->series->rows() < records)
      throw SolverError(path + " holds " + std::to_string(c->series->rows()) +
                        " steps, fewer than its checkpoint's " + std::to_string(records));
    c->series->truncate(records);
  }
  for (auto& s : snapshot_series_) {
    if (s->rows() < snapshots)
      throw SolverError(path + " holds fewer snapshots than its checkpoint's " +
                        std::to_string(snapshots));
    s->truncate(snapshots);
  }
  if (!snapshot_series_.empty()) snapshot_times_ = h5::read(file_, "/snapshots/time");
  for (const char* name : kSnapshotViews)
    for (std::size_t k = snapshots; h5::exists(file_, snapshot_view(name, k)); ++k)
      H5Ldelete(file_, snapshot_view(name, k).c_str(), H5P_DEFAULT);
  written_ = records;
  // What the end of the earlier run added beside each pantograph's series
  // (until 2026-12-06 the cross wind's: a restart of a windy run stopped at its end).
  for (auto& c : columns_) {
    const std::string group = c->path.substr(0, c->path.rfind('/'));
    for (const char* name : {kContactForceFiltered, kCrossWindForce, kHeadLateralOffset}) {
      const std::string added = group + "/" + name;
      if (h5::exists(file_, added)) H5Ldelete(file_, added.c_str(), H5P_DEFAULT);
    }
  }
}

void RunStream::stamp(const RunSettings& s) {
  h5::set_attribute(file_, "/", "complete", 0.0);
  h5::set_attribute(file_, "/", "analysis_from_x", s.analysis_from_x);
  h5::set_attribute(file_, "/", "analysis_to_x", s.analysis_to_x);
  h5::set_attribute(file_, "/", "speed_m_s", s.speed);
}

void RunStream::append(const contact::StepRecord& record, const EnergySample& energy) {
  for (auto& c : columns_) c->take(record, energy, c->pending);
  ++buffered_;
}

void RunStream::append_snapshot(const std::vector<double>& positions,
                                const contact::StepRecord& r) {
  if (file_ < 0) return;
  if (snapshot_series_.empty()) throw SolverError("results.h5: the run keeps no snapshots");
  guarded([&] { append_snapshot_rows(positions, r); });
}

void RunStream::append_snapshot_rows(const std::vector<double>& positions,
                                     const contact::StepRecord& r) {
  std::vector<double> displacement(positions);
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] -= layout_.static_positions[i];
  snapshot_series_[0]->append(&r.t, 1);
  snapshot_series_[1]->append(displacement.data(), 1);
  snapshot_series_[2]->append(r.contact_x.data(), 1);
  snapshot_series_[3]->append(r.contact_force.data(), 1);
  snapshot_series_[4]->append(r.wire_z.data(), 1);
  snapshot_series_[5]->append(pantograph_points(positions, r).data(), 1);
  const std::size_t k = snapshot_times_.size();
  const char* const units[] = {"m", "m", "N"};
  for (std::size_t v = 0; v < 3; ++v)
    h5::add_row_view(file_, snapshot_view(kSnapshotViews[v], k),
                     std::string("/snapshots/") + kSnapshotViews[v], k, units[v]);
  snapshot_times_.push_back(r.t);
}

// Head p: (x, y, head height), contact point: (x, y, wire height), y that of
// the contact wire at x (a record without head heights: the wire's).
std::vector<double> RunStream::pantograph_points(const std::vector<double>& positions,
                                                 const contact::StepRecord& r) const {
  std::vector<double> points;
  for (std::size_t p = 0; p < r.contact_x.size(); ++p) {
    const double x = r.contact_x[p], z = r.wire_z[p];
    const double head = p < r.head_z.size() ? r.head_z[p] : z;
    const double y = contact_y(layout_.contact_segments, positions, x, z);
    points.insert(points.end(), {x, y, head, x, y, z});
  }
  return points;
}

std::size_t RunStream::snapshots() const {
  return snapshot_series_.empty() ? 0 : snapshot_series_[0]->rows();
}

void RunStream::flush() {
  if (file_ < 0) return;
  guarded([&] { flush_rows(); });
}

void RunStream::flush_rows() {
  for (auto& c : columns_) {
    c->series->append(c->pending.data(), buffered_);
    c->pending.clear();
  }
  written_ += buffered_;
  buffered_ = 0;
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw SolverError("HDF5 could not flush it");
  last_flush_ = wall_seconds();
}

bool RunStream::flush_due() const {
  return buffered_ >= kMaxBufferedRows || (buffered_ > 0 && wall_seconds() - last_flush_ >= 1.0);
}

void RunStream::close() {
  if (file_ < 0) return;
  flush();
  guarded([&] {
    columns_.clear();
    snapshot_series_.clear();
    const herr_t status = H5Fclose(file_);
    file_ = -1;
    if (status < 0) throw SolverError("HDF5 could not close it");
  });
}

}  // namespace pcsim::output
