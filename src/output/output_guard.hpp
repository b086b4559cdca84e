// File-system helpers of OutputDir (rank 0 only): the manifest that marks a
// folder as pcsim's, the lock file, and the cleanup on SIGINT/SIGTERM.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace pcsim::output::guard {

// The manifest of 'dir' (dir/.pcsim-result); false if it is missing or is not
// a pcsim manifest.
bool read_manifest(const std::string& dir, nlohmann::json& manifest);
// Writes dir/.pcsim-result atomically (temporary file + rename); throws
// OutputError (the path, the OS error) if it cannot.
void write_manifest(const std::string& dir, const nlohmann::json& manifest);
// True if 'dir' is a folder whose only entry is its manifest.
bool holds_only_manifest(const std::string& dir);
// True if 'dir' is a folder that holds nothing, or only its manifest's
// temporary file: what a run killed between making its folder and writing
// its manifest leaves (no result in it).
bool holds_nothing_written(const std::string& dir);
// Current time, UTC, ISO 8601.
std::string utc_now();

// Takes the exclusive lock 'path' (flock on a file created if needed); returns
// the descriptor, or -1 with the reason in 'why' (who holds it, if known).
// 'owner' is written into the file for the message of a refused run.
int acquire_lock(const std::string& path, const std::string& owner, std::string& why);
// Deletes the lock file and releases the lock.
void release_lock(int fd, const std::string& path);

// Until disarmed, SIGINT and SIGTERM first remove 'partial' if it holds
// nothing but its manifest, and the lock file, then end the process as the
// signal would. An inherited SIG_IGN is kept. Returns false (nothing done)
// if another folder's cleanup is armed: only the one that armed it disarms it.
bool arm_interrupt_cleanup(const std::string& partial, const std::string& lock);
void disarm_interrupt_cleanup();

}  // namespace pcsim::output::guard
