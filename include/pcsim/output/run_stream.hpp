// results.h5 of `pcsim run`, written while the run goes (rank 0 only): every
// time series is an extendible, chunked dataset that grows by the rows of the
// accepted steps; rows wait in a small buffer and are written at flush(),
// which the run calls about once a second of wall time (flush_due()), so the
// memory does not grow with the length of the run and an interrupted run
// leaves its data up to the last flush. The root attribute 'complete' is 0
// until finish_run_results() (run_results.hpp) sets it to 1.
// Layout, shapes and units: docs/results-format.md.
#pragma once

#include <hdf5.h>

#include <array>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/contact/records.hpp"
#include "pcsim/output/run_results.hpp"

namespace pcsim::output {

namespace h5 {
class Series;
}

// What the datasets hold, fixed for a run.
struct RunLayout {
  std::vector<std::size_t> q_sizes;                // generalised coordinates per pantograph
  std::vector<std::vector<std::string>> q_labels;  // their names (model order)
  std::vector<double> support_x;                   // [m]
  std::vector<double> support_static_z;  // contact-wire height at the supports, static [m]
  std::size_t droppers = 0;              // dropper forces per step (0: not kept)
  std::size_t contact_wires = 0;         // force on each contact wire per pantograph (0: not kept)
  bool energy = false;                   // E(t) and the powers (output.energy)
  bool snapshots = false;                // field snapshots kept
  std::vector<double> static_positions;  // 3 per node: snapshots store the displacement from it
  // Node pairs of the contact wires' elements: a snapshot puts each contact
  // point on them (its y; none: y = 0).
  std::vector<std::array<int, 2>> contact_segments;
};

// The energy balance's values at a step (layout.energy; energy_results.hpp).
struct EnergySample {
  double energy = 0, power_external = 0, power_dissipative = 0;  // [J], [W], [W]
};

class RunStream {
 public:
  // Creates 'path' (replacing a file there) with every dataset empty and the
  // provenance (provenance.hpp) as root attributes.
  RunStream(const std::string& path, const RunSettings& settings, RunLayout layout,
            const nlohmann::json& provenance);
  // Continues 'path', a copy of an earlier run's results.h5: keeps its first
  // 'records' steps and 'snapshots' snapshots (what its checkpoint had),
  // drops what the end of that run added (filtered forces), sets complete = 0
  // and stamps this run's provenance.
  RunStream(const std::string& path, const RunSettings& settings, RunLayout layout,
            std::size_t records, std::size_t snapshots, const nlohmann::json& provenance);
  ~RunStream();
  RunStream(const RunStream&) = delete;
  RunStream& operator=(const RunStream&) = delete;

  // One accepted step (buffered); energy: only read with layout.energy.
  void append(const contact::StepRecord& record, const EnergySample& energy = {});
  // A field snapshot at the step appended last: node positions (3 per node)
  // and that step's pantograph positions and contact forces, the points of
  // every pantograph's head and contact point (written now).
  void append_snapshot(const std::vector<double>& positions, const contact::StepRecord& record);
  // Writes the buffered rows and flushes the file to disk.
  void flush();
  // True when a second of wall time has passed since the last flush, or the
  // buffer holds kMaxBufferedRows.
  bool flush_due() const;
  static constexpr std::size_t kMaxBufferedRows = 2000;

  std::size_t records() const { return written_ + buffered_; }
  std::size_t buffered_records() const { return buffered_; }
  std::size_t snapshots() const;
  std::vector<double> snapshot_times() const { return snapshot_times_; }
  // Flushes and closes the file (also done by the destructor).
  void close();
  // Creating, appending, flushing and closing throw OutputError (the path and
  // the OS error) when the file cannot be written; the file is then closed
  // and the stream writes nothing more (what was flushed before stays).

 private:
  struct Column;  // one dataset and its buffered rows
  using ColumnTake = std::function<void(const contact::StepRecord&, const EnergySample&,
                                        std::vector<double>&)>;  // appends a step's row
  void add_column(bool create, const std::string& path, std::vector<hsize_t> shape,
                  const std::string& unit, const std::string& description, ColumnTake take);
  void open_series(bool create, const RunSettings& settings);
  void open_pantograph_series(bool create, const std::string& name, std::size_t p);
  void open_snapshot_series(bool create, std::size_t pantographs);
  void reopen(const std::string& path, std::size_t records, std::size_t snapshots);
  void stamp(const RunSettings& settings);
  std::vector<double> pantograph_points(const std::vector<double>& positions,
                                        const contact::StepRecord& record) const;
  void create(const RunSettings& settings, const nlohmann::json& provenance);
  void append_snapshot_rows(const std::vector<double>& positions, const contact::StepRecord& r);
  void flush_rows();
  // Runs 'write'; on any failure closes the file as it is and throws OutputError.
  void guarded(const std::function<void()>& write);
  void abandon();  // closes every dataset and the file, ignoring errors

  std::string path_;
  RunLayout layout_;
  hid_t file_ = -1;
  int fd_ = -1;                                   // its OS descriptor (h5::discard_close)
  std::vector<std::unique_ptr<Column>> columns_;  // per-step series, in append order
  std::vector<std::unique_ptr<h5::Series>> snapshot_series_;
  std::vector<double> snapshot_times_;
  std::size_t written_ = 0, buffered_ = 0;
  double last_flush_ = 0;  // wall time [s]
};

}  // namespace pcsim::output
