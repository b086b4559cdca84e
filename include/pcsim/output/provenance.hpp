// Provenance of every result: what produced it, from what, where and when.
//
// The command (app) fills ProvenanceInputs; make_provenance() adds pcsim's
// version and git commit, the PETSc options database, the date and the host.
// The result travels with the output folder (OutputRequest::provenance) and
// the writers put it into summary.json ("provenance") and, with
// stamp_provenance(), as attributes of the root group of each HDF5 file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/output/h5_file.hpp"

namespace pcsim::output {

struct ProvenanceInputs {
  std::string command;                 // "run", "static", ...
  std::vector<std::string> arguments;  // the command line (argv)
  std::string scene_file;              // as given
  std::string scene_text;              // the scene file as written
  std::string resolved_scene;          // the composed scene (base, set, --set) as YAML
  std::vector<std::string> overrides;  // --set KEY=VALUE as given
  int ranks = 1;
  // Every input file as the command read it: [{role, path, sha256, content}]
  // (simulation::recorded_inputs), and one fingerprint over them.
  nlohmann::json inputs = nlohmann::json::array();
  std::string inputs_fingerprint;
};

// The version of this layout of summary.json and the HDF5 files' root
// attributes and datasets (docs/results-format.md).
constexpr int kResultsSchemaVersion = 2;

// {pcsim_version, git_commit, results_schema, command, command_line,
//  working_directory, scene_file, scene_text, resolved_scene, overrides,
//  inputs, inputs_fingerprint, petsc_options, ranks, date, host, cpu_model,
//  compiler, petsc_version, slepc_version, hdf5_version, mpi_version}
nlohmann::json make_provenance(const ProvenanceInputs& inputs);

// The command line as one shell-quoted string.
std::string quoted_command_line(const std::vector<std::string>& arguments);

// Every entry of 'provenance' as an attribute of the root group ("/"): text
// as strings, lists as arrays of strings (an empty list as ""), numbers as numbers.
void stamp_provenance(H5File& h5, const nlohmann::json& provenance);

}  // namespace pcsim::output
