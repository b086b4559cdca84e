// Results of `pcsim sweep`: one table of the EN 50318 figures of every case
// (and every pantograph of a case) against the swept values.
//   sweep.csv    case, the swept keys, pantograph, status, speed_kmh, then per
//                figure its value (display unit) and verdict (pass/fail, empty
//                where the standard gives no range)
//   sweep.md     the same as a Markdown table, values with their verdicts
//   sweep.h5     the same table, one dataset per column, each with its 'unit'
//                and 'description' attributes (output/h5_file.hpp): /case,
//                /values/<swept key>, /pantograph, /status, /exit_status,
//                /error, /speed_kmh, /figures/<figure key> (display unit,
//                NaN where none), /verdicts/<figure key>; written to a
//                temporary file, then renamed
//   summary.json {"swept": {key: [values]}, "cases": [{name, values, status,
//                 error, wall_s, cpu_s, summary}], "en50318": edition and
//                 figures, "provenance"}
//                and the entries of 'record' (pcsim sweep --cases: "cases_table"
//                {file, columns, rows, lines} and "sample", the table's design)
// The cases' own folders are cases/<case>/ (a pcsim run result each).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pcsim/output/output_dir.hpp"

namespace pcsim::output {

constexpr const char* kSweepH5Name = "sweep.h5";

struct SweepCase {
  std::string name;                                         // folder under cases/
  std::vector<std::pair<std::string, std::string>> values;  // swept key -> value
  int status = -1;                                          // exit status of its run (-1: none)
  nlohmann::json summary;                                   // its summary.json (null if none)
  std::string error;                                        // a failed run: its last log line
  double wall_s = 0, cpu_s = 0;                             // its cost
};

// Writes sweep.csv, sweep.md, summary.json and sweep.h5; returns the Markdown table.
std::string write_sweep_results(
    const OutputDir& out,
    const std::vector<std::pair<std::string, std::vector<std::string>>>& swept,
    const std::vector<SweepCase>& cases, const nlohmann::json& record = nlohmann::json::object());

}  // namespace pcsim::output
