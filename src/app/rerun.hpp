// `pcsim run --rerun DIR`: runs the record of an earlier result again. The
// result's summary.json holds its provenance (output/provenance.hpp): the
// scene file, the --set overrides, the PETSc options, the working directory
// and every input file's SHA-256 and content. The rerun composes the same
// scene from the same files and options; it refuses (exit 2) when an input
// file no longer has the recorded content, and warns when pcsim's version,
// commit or the number of ranks differ.
#pragma once

#include <string>
#include <vector>

#include "command.hpp"

namespace pcsim::app {

// Before PETSc starts: fills ctx (scene, overrides, default -o DIR-rerun) and
// the PETSc arguments from DIR's record. "" on success, else the reason
// (a usage error, exit 2).
std::string prepare_rerun(const std::string& dir, CommandContext& ctx,
                          std::vector<std::string>& petsc_arguments);

// After the scene is read: the recorded inputs against the files as they are
// now (InputError naming DIR's summary.json and the changed file); warnings
// for another version, commit or rank count (stderr, rank 0).
void check_rerun(const CommandContext& ctx, const scene::InputNode& scene);

}  // namespace pcsim::app
