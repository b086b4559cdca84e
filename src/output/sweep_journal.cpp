#include "pcsim/output/sweep_journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "pcsim/core/error.hpp"

namespace pcsim::output {

namespace {

// Writes all of 'text' to 'fd' and syncs it; the OS error, "" if none.
std::string write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return std::strerror(errno);
    done += static_cast<std::size_t>(n);
  }
  return fsync(fd) == 0 ? "" : std::strerror(errno);
}

void write_file(const std::string& file, const std::string& text, int flags) {
  const int fd = open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | flags, 0644);
  if (fd < 0) throw OutputError(file, std::strerror(errno));
  const std::string why = write_all(fd, text);
  if (close(fd) != 0 && why.empty()) throw OutputError(file, std::strerror(errno));
  if (!why.empty()) throw OutputError(file, why);
}

// Syncs the folder holding 'file' (its new or renamed entry survives a crash).
void sync_folder_of(const std::string& file) {
  const std::string dir = std::filesystem::path(file).parent_path().string();
  const int fd = open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  fsync(fd);
  close(fd);
}

// One line of JSON; text that is not UTF-8 (a log line) has its bad bytes replaced.
std::string line_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// The case lines of 'in' into the journal; with 'header', its first line is
// the header (false if it is not one).
bool read_lines(std::istream& in, SweepJournal& journal, bool header, std::string& why) {
  std::string line;
  bool first = header;
  while (std::getline(in, line)) {
    // A line without its newline was torn by a kill: dropped like an unreadable one.
    const bool whole = !in.eof();
    auto j = whole ? nlohmann::json::parse(line, nullptr, false) : nlohmann::json();
    if (first) {
      if (!j.is_object() || j.value("pcsim_sweep_journal", 0) != kSweepJournalVersion) {
        why = "its journal (" + std::string(kSweepJournalName) + ") has no readable first line";
        return false;
      }
      journal.header = j;
      first = false;
    } else if (j.is_object() && j.contains("case") && j.contains("status")) {
      journal.entries.push_back(j);
    } else if (!line.empty()) {
      ++journal.unreadable;
    }
  }
  if (first) why = "its journal (" + std::string(kSweepJournalName) + ") is empty";
  return !first;
}

}  // namespace

bool read_sweep_journal(const std::string& file, SweepJournal& journal, std::string& why) {
  journal = SweepJournal();
  std::ifstream in(file);
  if (!in) {
    why = "it has no journal (" + std::string(kSweepJournalName) + ")";
    return false;
  }
  return read_lines(in, journal, true, why);
}

std::string group_journal_name(int group) {
  return "journal-" + std::to_string(group) + ".jsonl";
}

std::size_t merge_group_journals(const std::string& file) {
  namespace fs = std::filesystem;
  std::vector<fs::path> groups;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(file).parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("journal-", 0) == 0 && e.path().extension() == ".jsonl")
      groups.push_back(e.path());
  }
  if (groups.empty()) return 0;
  SweepJournal journal;
  std::string why;
  if (!read_sweep_journal(file, journal, why)) throw OutputError(file, why);
  const std::size_t before = journal.entries.size();
  std::sort(groups.begin(), groups.end());
  for (const auto& g : groups) {
    std::ifstream in(g);
    read_lines(in, journal, false, why);
  }
  rewrite_sweep_journal(file, journal);
  for (const auto& g : groups) fs::remove(g, ec);
  return journal.entries.size() - before;
}

void append_sweep_journal(const std::string& file, const nlohmann::json& line) {
  const bool is_new = !std::filesystem::exists(file);
  write_file(file, line_text(line), O_APPEND);
  if (is_new) sync_folder_of(file);
}

void rewrite_sweep_journal(const std::string& file, const SweepJournal& journal) {
  std::string text = line_text(journal.header);
  for (const auto& e : journal.entries) text += line_text(e);
  const std::string tmp = file + ".tmp";
  write_file(tmp, text, O_TRUNC);
  if (std::rename(tmp.c_str(), file.c_str()) != 0) throw OutputError(file, std::strerror(errno));
  sync_folder_of(file);
}

}  // namespace pcsim::output
