// Checkpoint files of `pcsim run` (checkpoint.h5 in the output folder): named
// arrays of doubles (datasets) and named numbers and texts (attributes of the
// root group). The command decides what they hold (docs/results-format.md);
// this part only stores them. Written on rank 0, atomically: a temporary file
// renamed over the previous checkpoint, so that an interruption while writing
// keeps the previous one intact.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace pcsim::output {

struct CheckpointData {
  std::map<std::string, std::vector<double>> arrays;  // "/state/U" -> values
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts;
};

inline constexpr const char* kCheckpointName = "checkpoint.h5";

// Throws pcsim::SolverError if the file cannot be written.
void write_checkpoint(const std::string& path, const CheckpointData& data);
// Everything in the file; throws pcsim::SolverError naming the file if it is
// not a pcsim checkpoint or cannot be read.
CheckpointData read_checkpoint(const std::string& path);

}  // namespace pcsim::output
