// The cases of `pcsim sweep` as local processes (cmd_sweep.cpp plans them):
// up to N at a time, each finished case (success or failure) appended to the
// sweep's journal (output/sweep_journal.hpp) before anything else is done
// with it; a rerun into the same folder resumes from the journal; SIGINT and
// SIGTERM stop the running cases and leave the journal as it is. The
// journal's helpers below serve the MPI mode too (sweep_mpi.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/sweep_results.hpp"

namespace pcsim::app {

struct SweptKey {
  std::string key, given;  // the key path; the --set as given
  std::vector<std::string> values;
};

struct SweepPlan {
  std::vector<std::string> fixed;  // plain overrides, for every case
  std::vector<SweptKey> swept;
  std::vector<output::SweepCase> cases;
  std::vector<std::vector<std::string>> assignments;  // KEY=VALUE of each case
  std::vector<std::string> origins;                   // --cases: "FILE line N" of each case
  nlohmann::json table;                               // --cases: the table's record
  nlohmann::json sample;                              // --cases: its '# sample:' comment
  std::string table_text;                             // --cases: the file (fingerprint)
};

// What to do with the leftover partial folder of an interrupted sweep: resume
// it if its journal was written for 'definition', replace it if not and
// 'overwrite', else refuse ('why': the journal is missing or unreadable, or
// the definition differs).
output::OutputRequest::Leftover sweep_leftover(const std::string& partial, const std::string& definition,
                                       bool overwrite, std::string& why);

// Starts the journal of a new sweep, or reads that of a resumed one into the
// plan's cases (the finished ones get their status); returns the number of
// cases resumed.
std::size_t open_sweep_journal(SweepPlan& plan, const output::OutputDir& out,
                               const std::string& definition);

// Runs the cases the journal does not hold, 'jobs' at a time; returns the
// signal that stopped the sweep (0: none). Then fills the plan's cases from
// the journal (when not stopped).
int run_sweep_cases(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out, int jobs);

// The plan's cases from the journal (the tables are the journal's); throws
// OutputError if it lacks a case.
void fill_cases_from_journal(SweepPlan& plan, const output::OutputDir& out);

// `pcsim run SCENE -o FOLDER --no-report --set ...` of case k with the
// sweep's PETSc options (no accuracy pilot unless the sweep asks for one),
// behind mpiexec when --ranks asks for more than one.
std::vector<std::string> case_command(const CommandContext& ctx, const SweepPlan& plan,
                                      std::size_t k, const std::string& folder);

// A finished case's summary.json from its folder (null unless it ran to its
// end, status 0, and the file parses).
nlohmann::json read_case_summary(const std::string& folder, int status);

// The journal line of finished case k.
nlohmann::json journal_entry(const SweepPlan& plan, std::size_t k);

// A finished case in a few words: "ok, <pantograph>: mean .. N, sigma .. N"
// or "failed (exit N: error), see cases/<case>.log".
std::string case_line(const output::SweepCase& c);

// A case's leftovers from an interrupted sweep: its partial run folder (made
// by pcsim: it has the manifest) is removed, unless a run still holds its
// lock (a case process of a killed sweep left running).
void discard_case_leftovers(const std::string& folder);

}  // namespace pcsim::app
