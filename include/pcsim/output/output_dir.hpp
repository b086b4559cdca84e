// Output folder of one pcsim command, written so that no data is lost:
//  - results go to "<dir>.partial", which holds a manifest ".pcsim-result"
//    (JSON: command, scene, dates) marking it as pcsim's own;
//  - pcsim writes into, replaces or deletes only folders that it created (that
//    carry the manifest); "<dir>" must be new, empty or an earlier pcsim result,
//    and neither the working directory nor a folder containing it; an earlier
//    result is replaced only if it holds no file that pcsim did not write (the
//    manifest lists them) and was made from the same inputs (the manifest's
//    inputs_fingerprint), or with OutputRequest::overwrite (--overwrite);
//  - a lock "<dir>.pcsim-lock" (flock, released when the process ends) keeps a
//    second run from writing the same folder;
//  - commit() swaps: the old result is moved aside, the new one renamed into
//    place, and only then is the old one deleted; if a rename fails the new
//    results stay in "<dir>.partial" and the error names it;
//  - a failed run (exception) removes its partial folder; SIGINT/SIGTERM remove
//    it only while it holds nothing but the manifest;
//  - a leftover "<dir>.partial" of an interrupted run is refused, unless the
//    command can continue it (OutputRequest::leftover, `pcsim sweep`'s
//    journal): then it is resumed (kept and written into, never removed by
//    this run) or, if the command says so, replaced; one that holds nothing
//    but its manifest, or nothing written (a run killed before it wrote its
//    manifest), is replaced.
// Collective over the communicator: only rank 0 touches the file system, and
// every outcome is broadcast, so that all ranks succeed or throw together.
#pragma once

#include <mpi.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pcsim::output {

// What to create, and who asked (for the manifest and the error messages).
struct OutputRequest {
  std::string dir;         // the results folder
  std::string given_in;    // where the folder was given: "command line" or the scene file
  std::string given_by;    // the key that gave it: "-o" or "name"
  std::string command;     // pcsim command ("run", "static", ...)
  std::string scene_file;  // the scene, as given
  std::string scene_name;
  nlohmann::json provenance;  // output/provenance.hpp; written into every result file
  // An earlier result made from other inputs (provenance's inputs_fingerprint)
  // is replaced only when this is set (--overwrite).
  bool overwrite = false;
  // What to do with a leftover "<dir>.partial" that holds more than its
  // manifest (called on rank 0, under the lock, with that folder): refuse
  // (the reason in 'why', "" for the usual message), resume it or replace it.
  // Unset: refused with the usual message.
  enum class Leftover { refuse, resume, replace };
  std::function<Leftover(const std::string& partial, std::string& why)> leftover = nullptr;
  // SIGINT/SIGTERM before the commit remove a partial folder that holds only
  // its manifest and end the process. false: the caller handles them (a case
  // of a sweep under mpirun stops at its next step instead).
  bool cleanup_on_signal = true;
};

class OutputDir {
 public:
  // Throws InputError(given_in, given_by, reason) on every rank when the folder
  // cannot be used (OutputError when its manifest cannot be written); nothing
  // is touched then.
  OutputDir(MPI_Comm comm, OutputRequest request);
  ~OutputDir();  // removes the partial folder unless committed (or kept by a failed commit)
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  // Path of a file inside the (partial) folder.
  std::string file(const std::string& name) const;
  const std::string& final_dir() const { return final_; }
  // What produced the results (output/provenance.hpp), for the writers.
  const nlohmann::json& provenance() const { return request_.provenance; }
  const std::string& partial_dir() const { return partial_; }
  // True if the partial folder is a leftover that this run continues
  // (OutputRequest::leftover said resume).
  bool resumed() const { return resumed_; }
  // Puts the finished results in place of any earlier result (collective);
  // if the manifest cannot be written, throws OutputError and keeps the
  // results in the partial folder, not marked complete.
  void commit();
  // An interrupted run: leaves "<dir>.partial" with what it holds (its data
  // and checkpoint), releases the lock (collective). No final folder appears.
  void keep_partial();

  static constexpr const char* kManifestName = ".pcsim-result";

 private:
  std::string prepare();          // rank 0: checks, lock, partial folder; "" or the reason
  std::string swap_into_place();  // rank 0: the commit's renames; "" or the reason
  std::string take_leftover();    // rank 0: a leftover partial resumed, replaced or refused
  void undo();                    // rank 0: removes what this run made, releases the lock
  void disarm();                  // rank 0: the signal cleanup off, if this folder armed it
  [[noreturn]] void fail(const std::string& reason) const;

  MPI_Comm comm_;
  int rank_ = 0;
  OutputRequest request_;
  std::string final_, partial_, lock_path_, started_;
  std::string failed_path_;  // a file that could not be written: fail() throws OutputError
  std::vector<std::string> created_parents_;  // folders made for <dir>, removed on failure
  int lock_fd_ = -1;
  bool owns_partial_ = false;  // this run made partial_ (a leftover is never removed)
  bool committed_ = false;
  bool resumed_ = false;       // partial_ is a leftover this run continues
  bool keep_partial_ = false;  // a failed commit keeps the new results
  bool armed_ = false;         // this folder armed the signal cleanup (output_guard.hpp)
};

// Throws what OutputDir's constructor would throw for 'request', touching
// nothing (`pcsim check`; a lock held by a running pcsim is not looked at).
void check_output_request(MPI_Comm comm, const OutputRequest& request);

// Why 'name' cannot name an output folder ("" if it can): empty, ".", "..",
// or with a path separator.
std::string invalid_folder_name_reason(const std::string& name);

// The time now in UTC as the manifests write it (2026-11-27T09:30:00Z).
std::string utc_timestamp();

}  // namespace pcsim::output
