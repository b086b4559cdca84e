// The case table of `pcsim sweep SCENE --cases FILE.csv`: a header line of
// scene keys (each a key `--set` takes), then one line per case with a value
// for every key. Lines starting with '#' are comments; a comment
// `# sample: {JSON}` (postproc/sample.py) records the design that made the
// table. Fields are separated by commas; a field with a comma or a quote is
// quoted ("[1, 2]", "a ""b"""). Blank lines are skipped.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pcsim::app {

struct CaseTable {
  std::string path;                            // FILE.csv as given
  std::vector<std::string> columns;            // the scene keys
  std::vector<std::vector<std::string>> rows;  // one value per column
  std::vector<int> lines;                      // line number of each row
  nlohmann::json sample;                       // the '# sample:' comment, null if none
  std::string text;                            // the whole file (fingerprint)
};

// InputError (file = path) naming the reason: a missing or unreadable file,
// no header or no case, an empty or repeated key, a ragged row, an empty
// value, a bad quote, an unreadable '# sample:' comment, more than max_rows cases.
CaseTable read_case_table(const std::string& path, std::size_t max_rows);

}  // namespace pcsim::app
