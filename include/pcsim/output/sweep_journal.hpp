// The journal of `pcsim sweep`: journal.jsonl in the sweep's output folder,
// one JSON object per line, written so that a SIGKILL loses at most the line
// being written (each line one write() on a file opened O_APPEND, then
// fsync()):
//   line 1     {"pcsim_sweep_journal": 1, "definition": SHA-256 of the sweep's
//              definition, "cases": number of cases, "started": UTC}
//   then       one line per finished case (success or failure), in the order
//              they finished: {"case": name, "index": 0-based, "values":
//              {key: value}, "overrides": [KEY=VALUE ...], "status": exit
//              status, "error": last line of its log ("" on success),
//              "wall_s", "cpu_s": its cost, "finished": UTC, "summary": its
//              summary.json without the provenance (null for a failed case)}
// The sweep's tables (sweep_results.hpp) are built from it; a rerun of the
// same sweep into the same folder keeps its cases and runs the others.
// Under mpirun (docs/cluster.md) each group of ranks appends its cases to a
// file of its own, journal-<group>.jsonl (case lines only): a single file
// appended from several nodes is not safe on a network file system (NFS
// does not keep O_APPEND writes of two clients apart). Rank 0 merges them
// into journal.jsonl when the sweep ends or is resumed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pcsim::output {

constexpr const char* kSweepJournalName = "journal.jsonl";
constexpr int kSweepJournalVersion = 1;

struct SweepJournal {
  nlohmann::json header;                // the first line (null if none could be read)
  std::vector<nlohmann::json> entries;  // the cases' lines that could be read
  std::size_t unreadable = 0;           // lines dropped (a line torn by a kill)
};

// Reads 'file'; false (and 'why') if it is missing or its first line is not
// a journal header. Unreadable case lines are counted and left out.
bool read_sweep_journal(const std::string& file, SweepJournal& journal, std::string& why);

// Appends one line (write() + fsync()); throws OutputError if it cannot.
void append_sweep_journal(const std::string& file, const nlohmann::json& line);

// The case-line file of group 'group' of an MPI sweep: "journal-<group>.jsonl".
std::string group_journal_name(int group);

// Moves the case lines of the group files beside 'file' (journal-*.jsonl)
// into it (rewritten, then the group files removed; a kill in between leaves
// a case twice, which readers take once). Returns how many lines it moved;
// throws OutputError if it cannot.
std::size_t merge_group_journals(const std::string& file);

// Writes the journal anew (temporary file, fsync, rename): after a resume, a
// torn last line is gone. Throws OutputError if it cannot.
void rewrite_sweep_journal(const std::string& file, const SweepJournal& journal);

}  // namespace pcsim::output
