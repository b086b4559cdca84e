// The modal cache files this process wrote (rank 0's record), so that those a
// higher cut-off's data supersede can be removed: an accuracy pilot's raises
// used to leave the data and the assembled basis of every cut-off they
// tried (docs/benchmarks.md, "Superseded cache files removed").
#pragma once

#include <string>

#include "pcsim/simulation/context.hpp"

namespace pcsim::simulation {

// A file's modification time and size ("" if it is missing): a file renamed
// over is another.
std::string file_stamp(const std::string& file);

// The modal data of 'cache_key' at cutoff_hz, written to 'file' just now.
void note_data_written(const std::string& cache_key, double cutoff_hz, const std::string& file);
// A basis assembled from the data served as 'served' (data file@stamp),
// written to 'file' just now.
void note_basis_written(const std::string& served, const std::string& file);
// The file this process wrote the data of 'cache_key' at cutoff_hz to, if
// it is still what it wrote (its stamp); "" otherwise.
std::string unchanged_data_file(const std::string& cache_key, double cutoff_hz);

// Rank 0 removes the data this process wrote below kept_hz, and the bases
// it wrote from them, where it also wrote data of the same key at or above
// kept_hz that are still there (each file only if unchanged since: its
// stamp), and says so on the console if it removed any (an accuracy pilot
// that took kept_hz).
void remove_superseded_files(const Context& ctx, double kept_hz);

}  // namespace pcsim::simulation
