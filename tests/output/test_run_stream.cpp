// results.h5 streamed during a run (output/run_stream.hpp): rows go to
// extendible datasets, the memory stays bounded however long the run, the
// file is readable after every flush and marked incomplete until the end, and
// a restart keeps exactly the checkpoint's rows and snapshots.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "pcsim/output/run_stream.hpp"

namespace {

using pcsim::contact::StepRecord;
using pcsim::output::RunLayout;
using pcsim::output::RunSettings;
using pcsim::output::RunStream;
namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  TempDir() {
    char name[] = "/tmp/pcsim-stream-XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() { fs::remove_all(path); }
};

RunSettings settings() {
  RunSettings s;
  s.scene_name = "stream";
  s.speed = 80;
  s.analysis_from_x = 10;
  s.analysis_to_x = 20;
  s.pantograph_names = {"front", "rear"};
  return s;
}

nlohmann::json provenance() {
  return {{"command", "run"}, {"ranks", 2}, {"overrides", {"simulation.dt=0.001"}}};
}

// Two pantographs (2 and 3 coordinates), 4 supports, 6 droppers, 5 nodes.
RunLayout layout(bool snapshots) {
  RunLayout l;
  l.q_sizes = {2, 3};
  l.support_x = {0, 50, 100, 150};
  l.support_static_z = {5.3, 5.31, 5.32, 5.33};
  l.droppers = 6;
  l.snapshots = snapshots;
  for (int i = 0; i < 15; ++i) l.static_positions.push_back(0.5 * i);
  return l;
}

// Step i: every value a function of i and its place, so rows can be checked.
StepRecord record(std::size_t i) {
  StepRecord r;
  const double t = 1e-3 * static_cast<double>(i);
  r.t = t;
  r.contact_force = {100 + t, 200 + t};
  r.contact_x = {5 + 80 * t, 25 + 80 * t};
  r.wire_z = {5.3 + t, 5.4 + t};
  r.head_z = {5.301 + t, 5.401 + t};
  r.q = {{t, 2 * t}, {3 * t, 4 * t, 5 * t}};
  r.support_z = {5.3 + t, 5.31 + t, 5.32 + t, 5.33 + t};
  for (int d = 0; d < 6; ++d) r.dropper_force.push_back(d + t);
  return r;
}

std::vector<double> read(const std::string& file, const std::string& set,
                         std::vector<hsize_t>* dims = nullptr) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  hid_t d = H5Dopen2(f, set.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << set;
  hid_t space = H5Dget_space(d);
  std::vector<hsize_t> shape(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, shape.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t s : shape) n *= s;
  std::vector<double> values(n);
  if (n > 0) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  if (dims) *dims = shape;
  return values;
}

bool exists(const std::string& file, const std::string& set) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  bool found = true;
  std::size_t pos = 0;
  do {
    pos = set.find('/', pos + 1);
    found = found && H5Lexists(f, set.substr(0, pos).c_str(), H5P_DEFAULT) > 0;
  } while (found && pos != std::string::npos);
  H5Fclose(f);
  return found;
}

double complete_flag(const std::string& file) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  double value = -1;
  hid_t a = H5Aopen(f, "complete", H5P_DEFAULT);
  H5Aread(a, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(a);
  H5Fclose(f);
  return value;
}

// Resident memory now [MB] (VmRSS).
double resident_mb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  double kb = 0;
  while (status >> key)
    if (key == "VmRSS:") {
      status >> kb;
      break;
    }
  return kb / 1024.0;
}

TEST(RunStream, RowsAreWrittenAsTheyComeAndReadBack) {
  TempDir dir;
  const std::string file = (dir.path / "results.h5").string();
  RunStream stream(file, settings(), layout(false), provenance());
  for (std::size_t i = 0; i < 10; ++i) stream.append(record(i));
  EXPECT_EQ(stream.records(), 10u);
  stream.flush();
  // Readable between flushes (the writer still has it open), not complete.
  std::vector<hsize_t> dims;
  EXPECT_EQ(read(file, "/time", &dims).size(), 10u);
  EXPECT_DOUBLE_EQ(complete_flag(file), 0.0);
  for (std::size_t i = 10; i < 25; ++i) stream.append(record(i));
  stream.close();
  const auto time = read(file, "/time");
  const auto q = read(file, "/pantographs/rear/q", &dims);
  const auto uplift = read(file, "/supports/uplift");
  const auto droppers = read(file, "/droppers/force");
  ASSERT_EQ(time.size(), 25u);
  EXPECT_EQ(dims, (std::vector<hsize_t>{25, 3}));
  for (std::size_t i = 0; i < 25; ++i) {
    const StepRecord r = record(i);
    EXPECT_EQ(time[i], r.t);
    EXPECT_EQ(q[3 * i + 2], r.q[1][2]);
    EXPECT_EQ(read(file, "/pantographs/front/contact_force")[i], r.contact_force[0]);
    // Uplift: height minus the static height (exact up to one rounding).
    EXPECT_NEAR(uplift[4 * i + 3], r.t, 1e-15);
    EXPECT_EQ(droppers[6 * i + 5], r.dropper_force[5]);
  }
  EXPECT_EQ(read(file, "/supports/x"), layout(false).support_x);
}

// A line with two contact wires and output.energy: the force on each wire and
// E(t) with the powers are series of their own, and the provenance is stamped
// on the root.
TEST(RunStream, WireForcesEnergyAndProvenance) {
  TempDir dir;
  const std::string file = (dir.path / "results.h5").string();
  RunLayout l = layout(false);
  l.contact_wires = 2;
  l.energy = true;
  {
    RunStream stream(file, settings(), l, provenance());
    for (std::size_t i = 0; i < 4; ++i) {
      StepRecord r = record(i);
      r.wire_force = {{1.0 * i, 2.0 * i}, {3.0 * i}};  // the rear one touches one wire
      pcsim::output::EnergySample e;
      e.energy = 10.0 + i;
      e.power_external = 0.5 * i;
      e.power_dissipative = -0.25 * i;
      stream.append(r, e);
    }
  }
  std::vector<hsize_t> dims;
  EXPECT_EQ(read(file, "/pantographs/front/wire_force", &dims),
            (std::vector<double>{0, 0, 1, 2, 2, 4, 3, 6}));
  EXPECT_EQ(dims, (std::vector<hsize_t>{4, 2}));
  // A wire the record does not name carries no force.
  EXPECT_EQ(read(file, "/pantographs/rear/wire_force"),
            (std::vector<double>{0, 0, 3, 0, 6, 0, 9, 0}));
  EXPECT_EQ(read(file, "/energy/energy"), (std::vector<double>{10, 11, 12, 13}));
  EXPECT_EQ(read(file, "/energy/power_dissipative"), (std::vector<double>{0, -0.25, -0.5, -0.75}));
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GT(H5Aexists(f, "command"), 0);
  EXPECT_GT(H5Aexists(f, "overrides"), 0);
  double ranks = 0;
  hid_t a = H5Aopen(f, "ranks", H5P_DEFAULT);
  H5Aread(a, H5T_NATIVE_DOUBLE, &ranks);
  H5Aclose(a);
  H5Fclose(f);
  EXPECT_EQ(ranks, 2.0);
}

// 200 000 steps of 96 values would be 150 MB in memory; the stream keeps at
// most kMaxBufferedRows of them (1.5 MB). Measured growth of the resident
// memory: 2.9 MB, HDF5's chunk caches (256 KiB for each of the 11 datasets)
// and the buffer; 8 MB leaves room for the allocator's slack and is still a
// twentieth of what keeping the history would take.
TEST(RunStream, MemoryDoesNotGrowWithTheRun) {
  TempDir dir;
  const std::string file = (dir.path / "results.h5").string();
  RunStream stream(file, settings(), layout(false), provenance());
  const double before = resident_mb();
  const StepRecord r = record(7);
  const std::size_t steps = 200000;
  for (std::size_t i = 0; i < steps; ++i) {
    stream.append(r);
    ASSERT_LE(stream.buffered_records(), RunStream::kMaxBufferedRows);
    if (stream.flush_due()) stream.flush();
  }
  const double growth = resident_mb() - before;
  stream.close();
  EXPECT_LT(growth, 8.0) << "resident memory grew by " << growth << " MB";
  EXPECT_EQ(read(file, "/time").size(), steps);
}

// The pantographs of the snapshots (SnapshotsAreOneDatasetWithViewsForXdmf):
// head and contact point of each, their views, lines and zero displacement.
void check_pantograph_points(const std::string& file) {
  std::vector<hsize_t> dims;
  const auto points = read(file, "/snapshots/pantograph_points", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{3, 4, 3}));
  for (std::size_t k = 0; k < 3; ++k) {
    const StepRecord r = record(k);
    const double* row = &points[12 * k];
    // Pantograph 0 is over the wire (y = x + 0.5 there, to rounding: 1e-12 m
    // is a few ulps of 10 m); pantograph 1 beyond its end (y = 0).
    const std::vector<double> expected = {r.contact_x[0],
                                          r.contact_x[0] + 0.5,
                                          r.head_z[0],
                                          r.contact_x[0],
                                          r.contact_x[0] + 0.5,
                                          r.wire_z[0],
                                          r.contact_x[1],
                                          0.0,
                                          r.head_z[1],
                                          r.contact_x[1],
                                          0.0,
                                          r.wire_z[1]};
    for (std::size_t i = 0; i < 12; ++i) EXPECT_NEAR(row[i], expected[i], 1e-12) << k << " " << i;
    const auto view = read(file, "/snapshots/xdmf/pantograph_points_" + std::to_string(k), &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{4, 3}));
    EXPECT_EQ(view, std::vector<double>(row, row + 12));
    EXPECT_EQ(read(file, "/snapshots/xdmf/contact_force_" + std::to_string(k)), r.contact_force);
  }
  EXPECT_EQ(read(file, "/snapshots/xdmf/pantograph_cells", &dims),
            (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 2}));
  EXPECT_EQ(read(file, "/snapshots/xdmf/pantograph_displacement", &dims),
            std::vector<double>(12, 0.0));
}

TEST(RunStream, SnapshotsAreOneDatasetWithViewsForXdmf) {
  TempDir dir;
  const std::string file = (dir.path / "results.h5").string();
  RunLayout l = layout(true);
  // The contact wire: nodes 0-4 in a line, where y = x + 0.5.
  l.contact_segments = {{0, 1}, {1, 2}, {2, 3}, {3, 4}};
  {
    RunStream stream(file, settings(), l, provenance());
    for (std::size_t i = 0; i < 3; ++i) {
      const StepRecord r = record(i);
      stream.append(r);
      std::vector<double> positions = l.static_positions;
      for (double& p : positions) p += static_cast<double>(i);
      stream.append_snapshot(positions, r);
    }
    EXPECT_EQ(stream.snapshots(), 3u);
  }
  std::vector<hsize_t> dims;
  const auto displacement = read(file, "/snapshots/displacement", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{3, 5, 3}));
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(displacement[15 * k + 7], static_cast<double>(k));
    // The XDMF's per-snapshot view reads the same values.
    const auto view = read(file, "/snapshots/xdmf/displacement_" + std::to_string(k), &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{5, 3}));
    EXPECT_EQ(view, std::vector<double>(displacement.begin() + 15 * k,
                                        displacement.begin() + 15 * (k + 1)));
  }
  EXPECT_EQ(read(file, "/snapshots/contact_force", &dims)[2 * 2 + 1], record(2).contact_force[1]);
  EXPECT_EQ(dims, (std::vector<hsize_t>{3, 2}));
  check_pantograph_points(file);
}

// A restart continues a copy of the earlier results.h5: what came after the
// checkpoint (rows, snapshots and their views, the filtered forces of a
// finished run) is dropped, and the file is incomplete again.
TEST(RunStream, RestartKeepsTheCheckpointsRows) {
  TempDir dir;
  const std::string file = (dir.path / "results.h5").string();
  const RunLayout l = layout(true);
  {
    RunStream stream(file, settings(), l, provenance());
    for (std::size_t i = 0; i < 12; ++i) {
      stream.append(record(i));
      if (i % 4 == 0) stream.append_snapshot(l.static_positions, record(i));
    }
  }
  {
    hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    hsize_t n = 1;
    hid_t space = H5Screate_simple(1, &n, nullptr);
    hid_t d = H5Dcreate2(f, "/pantographs/front/contact_force_filtered", H5T_NATIVE_DOUBLE, space,
                         H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(d);
    H5Sclose(space);
    H5Fclose(f);
  }
  {
    RunStream stream(file, settings(), l, 6, 2,
                     provenance());  // checkpoint at step 5: 6 rows, 2 snapshots
    EXPECT_EQ(stream.records(), 6u);
    EXPECT_EQ(stream.snapshots(), 2u);
    EXPECT_EQ(stream.snapshot_times(), (std::vector<double>{0.0, 0.004}));
    EXPECT_DOUBLE_EQ(complete_flag(file), 0.0);
    for (std::size_t i = 6; i < 9; ++i) stream.append(record(i));
  }
  const auto time = read(file, "/time");
  ASSERT_EQ(time.size(), 9u);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(time[i], record(i).t);
  EXPECT_EQ(read(file, "/snapshots/time").size(), 2u);
  for (const char* view : {"displacement", "pantograph_points", "contact_force"}) {
    EXPECT_TRUE(exists(file, std::string("/snapshots/xdmf/") + view + "_1")) << view;
    EXPECT_FALSE(exists(file, std::string("/snapshots/xdmf/") + view + "_2")) << view;
  }
  EXPECT_FALSE(exists(file, "/pantographs/front/contact_force_filtered"));
  // Fewer rows than the checkpoint needs: refused.
  EXPECT_THROW(RunStream(file, settings(), l, 20, 2, provenance()), std::exception);
}

}  // namespace
