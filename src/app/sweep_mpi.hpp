// The cases of `pcsim sweep` under mpirun (docs/cluster.md): the ranks are
// split into groups of -sweep_ranks_per_case ranks; every group's first rank
// claims the next case from a counter that world rank 0 exposes
// (MPI_Fetch_and_op, passive target: no rank waits as a manager), and the
// group runs it in-process as `pcsim run` (run_scene_command) on its own
// communicator, into cases/<case>/ as the local mode does, its console in
// cases/<case>.log. A failed case is journaled with its error and the group
// goes on. Each group appends its finished cases to journal-<group>.jsonl
// (output/sweep_journal.hpp); rank 0 merges them into journal.jsonl.
// SIGINT/SIGTERM: no case is claimed any more, the running ones stop at
// their next step (kept in cases/<case>.partial, run again on a resume).
#pragma once

#include "command.hpp"
#include "pcsim/output/output_dir.hpp"
#include "sweep_runner.hpp"

namespace pcsim::app {

constexpr const char* kRanksPerCaseOption = "-sweep_ranks_per_case";

// -sweep_ranks_per_case (1 if not given; declared so that -help lists it).
// InputError naming the option, on every rank, if it is not a whole number
// >= 1 that divides the number of ranks.
int sweep_ranks_per_case(const CommandContext& ctx);

// Runs the cases the journal does not hold (collective on ctx.comm; the
// plan's statuses must be the same on every rank). Returns the signal that
// stopped the sweep (0: none); either way the finished cases are in
// journal.jsonl (rank 0 merged the groups' files) when it returns.
int run_sweep_cases_mpi(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out,
                        int ranks_per_case);

}  // namespace pcsim::app
