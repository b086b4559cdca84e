#include "cache_written.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <vector>

namespace pcsim::simulation {

namespace {

struct WrittenFile {
  std::string file, stamp;
  bool unchanged() const { return !stamp.empty() && file_stamp(file) == stamp; }
};

struct WrittenData {
  std::string cache_key;
  double cutoff_hz = 0;
  WrittenFile data;
  std::vector<WrittenFile> bases;
};

std::vector<WrittenData> written;

std::string stamp_of(const struct stat& st) {
  return std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ":" +
         std::to_string(st.st_size);
}

// Removes 'f' if it is still what this process wrote; its bytes, or 0.
double remove_unchanged(const WrittenFile& f) {
  struct stat st {};
  if (f.stamp.empty() || stat(f.file.c_str(), &st) != 0 || stamp_of(st) != f.stamp) return 0;
  return std::remove(f.file.c_str()) == 0 ? static_cast<double>(st.st_size) : 0;
}

bool superseded(const WrittenData& d, double kept_hz) {
  if (d.cutoff_hz <= 0 || d.cutoff_hz >= kept_hz) return false;
  for (const auto& e : written)
    if (e.cache_key == d.cache_key && e.cutoff_hz >= kept_hz && e.data.unchanged()) return true;
  return false;
}

// The bytes removed.
double remove_superseded_data(double kept_hz) {
  std::vector<char> removed(written.size());
  for (std::size_t i = 0; i < written.size(); ++i) removed[i] = superseded(written[i], kept_hz);
  double bytes = 0;
  std::vector<WrittenData> kept;
  for (std::size_t i = 0; i < written.size(); ++i) {
    if (!removed[i]) {
      kept.push_back(std::move(written[i]));
      continue;
    }
    for (const auto& b : written[i].bases) bytes += remove_unchanged(b);
    bytes += remove_unchanged(written[i].data);
  }
  written = std::move(kept);
  return bytes;
}

}  // namespace

std::string file_stamp(const std::string& file) {
  struct stat st {};
  return stat(file.c_str(), &st) == 0 ? stamp_of(st) : "";
}

void note_data_written(const std::string& cache_key, double cutoff_hz, const std::string& file) {
  written.push_back({cache_key, cutoff_hz, {file, file_stamp(file)}, {}});
}

void note_basis_written(const std::string& served, const std::string& file) {
  for (auto& d : written)
    if (served == d.data.file + "@" + d.data.stamp) d.bases.push_back({file, file_stamp(file)});
}

std::string unchanged_data_file(const std::string& cache_key, double cutoff_hz) {
  for (const auto& d : written)
    if (d.cache_key == cache_key && d.cutoff_hz == cutoff_hz && d.data.unchanged())
      return d.data.file;
  return "";
}

void remove_superseded_files(const Context& ctx, double kept_hz) {
  const double bytes = ctx.rank == 0 && kept_hz > 0 ? remove_superseded_data(kept_hz) : 0;
  if (bytes > 0)
    print0(ctx,
           "    the cache's files of the cut-offs below %.1f Hz removed (%.2f GB): the data at "
           "%.1f Hz serve them\n",
           kept_hz, bytes / 1e9, kept_hz);
}

}  // namespace pcsim::simulation
