#include "pcsim/output/output_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "output_guard.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/vec_root.hpp"

namespace fs = std::filesystem;

namespace pcsim::output {

namespace {

// True if 'inner' is 'outer' or lies inside it (both absolute and normal).
bool is_inside(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

std::string in_quotes(const std::string& path) {
  return "'" + path + "'";
}

// The files below 'dir' (relative paths, the manifest left out).
std::vector<std::string> files_below(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (!it->is_directory(ec)) {
      const std::string rel = fs::relative(it->path(), dir, ec).string();
      if (rel != OutputDir::kManifestName) files.push_back(rel);
    }
  std::sort(files.begin(), files.end());
  return files;
}

// The request's inputs fingerprint ("" when its provenance has none).
std::string fingerprint(const OutputRequest& request) {
  return request.provenance.is_object()
             ? request.provenance.value("inputs_fingerprint", std::string())
             : std::string();
}

// Why an earlier pcsim result at 'dir' may not be replaced by this request
// ("" if it may): it was made from other inputs (unless --overwrite), or it
// holds files that pcsim did not write (its manifest lists those it wrote).
std::string replacement_refusal(const std::string& dir, const nlohmann::json& existing,
                                const OutputRequest& request) {
  if (existing.contains("files")) {
    std::vector<std::string> added;
    for (const auto& f : files_below(dir))
      if (std::find(existing["files"].begin(), existing["files"].end(), f) ==
          existing["files"].end())
        added.push_back(f);
    if (!added.empty()) {
      std::string list;
      for (std::size_t i = 0; i < added.size() && i < 10; ++i) list += (i ? ", " : "") + added[i];
      if (added.size() > 10) list += ", ... (" + std::to_string(added.size()) + " in all)";
      return in_quotes(dir) + " holds files that pcsim did not write (" + list +
             "); pcsim replaces its results as a whole: move them away, or give another "
             "folder with -o";
    }
  }
  const std::string was = existing.value("inputs_fingerprint", std::string());
  const std::string now = fingerprint(request);
  if (request.overwrite || was.empty() || now.empty() || was == now) return "";
  return in_quotes(dir) + " holds the result of other inputs (pcsim " +
         existing.value("command", std::string("?")) + " " +
         existing.value("scene_file", std::string("?")) + ", finished " +
         existing.value("finished", std::string("?")) +
         "); give --overwrite to replace it, or another folder with -o";
}

// Why pcsim may not put its results at 'dir' ("" if it may): the working
// directory or a folder containing it, a folder holding the scene, a link, a
// file, a non-empty folder that is not an earlier pcsim result, or one that
// may not be replaced (replacement_refusal).
std::string target_refusal(const std::string& dir, const OutputRequest& request) {
  const std::string& scene_file = request.scene_file;
  const std::string whole =
      "pcsim replaces its output folder as a whole, so it must be new, "
      "empty or an earlier pcsim result";
  const fs::path target = fs::weakly_canonical(fs::absolute(dir));
  const fs::path cwd = fs::current_path();
  if (target == cwd) return in_quotes(dir) + " is the working directory; " + whole;
  if (is_inside(cwd, target)) return in_quotes(dir) + " contains the working directory; " + whole;
  std::error_code ec;
  if (!scene_file.empty() && fs::exists(scene_file, ec) &&
      is_inside(fs::weakly_canonical(fs::absolute(scene_file)), target))
    return in_quotes(dir) + " holds the scene file " + scene_file + "; " + whole;
  const auto status = fs::symlink_status(dir, ec);
  if (status.type() == fs::file_type::not_found) return "";
  if (status.type() == fs::file_type::symlink)
    return in_quotes(dir) + " is a symbolic link; give the folder it points to";
  if (status.type() != fs::file_type::directory)
    return in_quotes(dir) + " exists and is not a folder";
  nlohmann::json existing;
  if (fs::is_empty(dir)) return "";
  if (!guard::read_manifest(dir, existing))
    return in_quotes(dir) + " is not empty and was not written by pcsim (it has no " +
           OutputDir::kManifestName + "); " + whole;
  return replacement_refusal(dir, existing, request);
}

// A leftover "<dir>.partial" from an interrupted run: removed (if 'remove')
// when it holds nothing but its manifest, or nothing written at all (a run
// killed before its manifest), else kept and the run refused ("" if none left).
std::string leftover_partial_refusal(const std::string& partial, bool remove = true) {
  std::error_code ec;
  const auto status = fs::symlink_status(partial, ec);
  if (status.type() == fs::file_type::not_found) return "";
  nlohmann::json m;
  const bool folder = status.type() == fs::file_type::directory;
  if (folder && guard::holds_nothing_written(partial)) {  // killed before its manifest
    if (remove) fs::remove_all(partial);
    return "";
  }
  if (!folder || !guard::read_manifest(partial, m))
    return in_quotes(partial) + " exists and was not written by pcsim; move it away";
  if (guard::holds_only_manifest(partial)) {
    if (remove) fs::remove_all(partial);
    return "";
  }
  const bool restartable = fs::exists(partial + "/checkpoint.h5", ec);
  return in_quotes(partial) + " holds the results of an interrupted pcsim run (" +
         m.value("command", std::string("?")) + " " + m.value("scene_file", std::string("?")) +
         ", started " + m.value("started", std::string("?")) + "); " +
         (restartable ? "continue it with --restart " + partial + " -o ANOTHER_FOLDER, or " : "") +
         "move it away or delete it, then run again";
}

std::string normal_form(const std::string& dir) {
  std::string normal = fs::path(dir).lexically_normal().string();
  while (normal.size() > 1 && normal.back() == '/') normal.pop_back();
  return normal;
}

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

// complete: the results are all in 'dir'; the manifest then lists its files.
nlohmann::json manifest(const OutputRequest& request, const std::string& started, bool complete,
                        const std::string& dir) {
  nlohmann::json m = {{"pcsim_result", 1},
                      {"command", request.command},
                      {"scene_file", request.scene_file},
                      {"scene_name", request.scene_name},
                      {"started", started},
                      {"host", host_name()},
                      {"pid", static_cast<long>(getpid())},
                      {"complete", complete},
                      {"inputs_fingerprint", fingerprint(request)}};
  if (complete) {
    m["finished"] = guard::utc_now();
    m["files"] = files_below(dir);
  }
  return m;
}

}  // namespace

std::string utc_timestamp() {
  return guard::utc_now();
}

std::string invalid_folder_name_reason(const std::string& name) {
  if (name.empty()) return "must not be empty (it names the output folder out/<name>)";
  if (name == "." || name == "..")
    return "must not be '" + name + "' (it names the output folder out/<name>)";
  if (name.find_first_of("/\\") != std::string::npos)
    return "must not contain a path separator (it names the output folder out/<name>; "
           "use -o to choose another folder)";
  if (name.find('\0') != std::string::npos) return "must not contain a NUL character";
  return "";
}

void check_output_request(MPI_Comm comm, const OutputRequest& request) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string why;
  if (rank == 0) {
    try {
      const std::string dir = normal_form(request.dir);
      why = request.dir.empty() ? "the output folder is empty" : target_refusal(dir, request);
      if (why.empty()) why = leftover_partial_refusal(dir + ".partial", false);
    } catch (const std::exception& e) {
      why = std::string("cannot check the output folder: ") + e.what();
    }
  }
  why = broadcast_text(comm, why);
  if (!why.empty()) throw InputError(request.given_in, request.given_by, why);
}

OutputDir::OutputDir(MPI_Comm comm, OutputRequest request)
    : comm_(comm), request_(std::move(request)) {
  MPI_Comm_rank(comm_, &rank_);
  final_ = normal_form(request_.dir);
  partial_ = final_ + ".partial";
  lock_path_ = final_ + ".pcsim-lock";
  std::string why;
  if (rank_ == 0) why = prepare();
  why = broadcast_text(comm_, why);
  failed_path_ = broadcast_text(comm_, failed_path_);
  resumed_ = broadcast_text(comm_, resumed_ ? "1" : "") == "1";
  if (!why.empty()) fail(why);
}

std::string OutputDir::prepare() {
  try {
    if (request_.dir.empty()) return "the output folder is empty";
    std::string why = target_refusal(final_, request_);
    if (!why.empty()) return why;
    // Parent folders: made now, removed again if the run fails.
    std::vector<fs::path> missing;
    for (fs::path p = fs::absolute(final_).parent_path(); !fs::exists(p); p = p.parent_path())
      missing.push_back(p);
    for (auto p = missing.rbegin(); p != missing.rend(); ++p) {
      fs::create_directory(*p);
      created_parents_.push_back(p->string());
    }
    const std::string owner = "pcsim " + request_.command + " " + request_.scene_file + ", pid " +
                              std::to_string(getpid()) + " on " + host_name() + ", started " +
                              guard::utc_now();
    lock_fd_ = guard::acquire_lock(lock_path_, owner, why);
    // Under the lock: the folder may have changed since the check above.
    if (why.empty()) why = target_refusal(final_, request_);
    if (why.empty()) why = take_leftover();
    if (why.empty() && !resumed_) {
      fs::create_directory(partial_);
      owns_partial_ = true;
      started_ = guard::utc_now();
      guard::write_manifest(partial_, manifest(request_, started_, false, partial_));
    }
    if (why.empty() && request_.cleanup_on_signal)
      armed_ = guard::arm_interrupt_cleanup(partial_, lock_path_);
    if (!why.empty()) undo();
    return why;
  } catch (const OutputError& e) {
    undo();
    failed_path_ = e.path();
    return e.reason();
  } catch (const std::exception& e) {
    undo();
    return std::string("cannot prepare the output folder: ") + e.what();
  }
}

// A leftover partial folder: one holding only its manifest is removed; else
// the request's 'leftover' decides (a resumed one is not this run's to remove).
std::string OutputDir::take_leftover() {
  std::error_code ec;
  nlohmann::json m;
  if (!request_.leftover || !fs::is_directory(fs::symlink_status(partial_, ec)) ||
      !guard::read_manifest(partial_, m) || guard::holds_only_manifest(partial_))
    return leftover_partial_refusal(partial_);
  std::string why;
  switch (request_.leftover(partial_, why)) {
    case OutputRequest::Leftover::resume:
      resumed_ = true;
      started_ = m.value("started", guard::utc_now());
      return "";
    case OutputRequest::Leftover::replace:
      fs::remove_all(partial_);
      return "";
    default:
      return why.empty() ? leftover_partial_refusal(partial_) : why;
  }
}

void OutputDir::disarm() {
  if (armed_) guard::disarm_interrupt_cleanup();
  armed_ = false;
}

// Rank 0, on failure: removes what this run made (not a kept partial folder).
void OutputDir::undo() {
  disarm();
  std::error_code ec;
  if (owns_partial_ && !keep_partial_) fs::remove_all(partial_, ec);
  guard::release_lock(lock_fd_, lock_path_);
  lock_fd_ = -1;
  if (!keep_partial_)
    for (auto p = created_parents_.rbegin(); p != created_parents_.rend(); ++p)
      fs::remove(*p, ec);  // only if empty
  created_parents_.clear();
}

OutputDir::~OutputDir() {
  if (rank_ == 0 && !committed_) undo();
}

std::string OutputDir::file(const std::string& name) const {
  return partial_ + "/" + name;
}

void OutputDir::commit() {
  MPI_Barrier(comm_);
  std::string why;
  if (rank_ == 0) {
    try {
      why = swap_into_place();
    } catch (const OutputError& e) {
      keep_partial_ = true;  // not marked complete: its manifest is the earlier one
      failed_path_ = e.path();
      why = e.reason() + "; the results are kept in " + partial_;
    } catch (const std::exception& e) {
      keep_partial_ = true;
      why = std::string("cannot put the results in place: ") + e.what() +
            "; the new results are kept in " + partial_;
    }
    if (why.empty()) {
      committed_ = true;
      disarm();
      guard::release_lock(lock_fd_, lock_path_);
      lock_fd_ = -1;
    }
  }
  why = broadcast_text(comm_, why);
  failed_path_ = broadcast_text(comm_, failed_path_);
  if (!why.empty()) fail(why);
  committed_ = true;
}

void OutputDir::keep_partial() {
  MPI_Barrier(comm_);
  if (rank_ == 0) {
    keep_partial_ = true;
    disarm();
    guard::release_lock(lock_fd_, lock_path_);
    lock_fd_ = -1;
    created_parents_.clear();
  }
  committed_ = true;  // nothing left to undo
}

std::string OutputDir::swap_into_place() {
  const std::string kept = "; the new results are kept in " + partial_;
  guard::write_manifest(partial_, manifest(request_, started_, true, partial_));
  // The folder may have been changed by hand during the run.
  std::string why = target_refusal(final_, request_);
  if (!why.empty()) {
    keep_partial_ = true;
    return why + kept;
  }
  std::error_code ec;
  std::string old;
  if (fs::symlink_status(final_, ec).type() != fs::file_type::not_found) {
    old = final_ + ".pcsim-old-" + std::to_string(getpid());
    for (int k = 1; fs::symlink_status(old, ec).type() != fs::file_type::not_found; ++k)
      old = final_ + ".pcsim-old-" + std::to_string(getpid()) + "-" + std::to_string(k);
    fs::rename(final_, old, ec);
    if (ec) {
      keep_partial_ = true;
      return "cannot move the earlier result " + in_quotes(final_) + " aside: " + ec.message() +
             kept;
    }
  }
  fs::rename(partial_, final_, ec);
  if (ec) {
    keep_partial_ = true;
    why = "cannot rename " + in_quotes(partial_) + " to " + in_quotes(final_) + ": " +
          ec.message() + kept;
    if (!old.empty()) {
      std::error_code back;
      fs::rename(old, final_, back);
      if (back) why += ", the earlier result in " + old;
    }
    return why;
  }
  if (!old.empty()) {
    fs::remove_all(old, ec);
    if (ec)
      std::fprintf(stderr, "pcsim: warning: could not delete the earlier result, moved to %s: %s\n",
                   old.c_str(), ec.message().c_str());
  }
  return "";
}

void OutputDir::fail(const std::string& reason) const {
  if (!failed_path_.empty()) throw OutputError(failed_path_, reason);
  throw InputError(request_.given_in, request_.given_by, reason);
}

}  // namespace pcsim::output
