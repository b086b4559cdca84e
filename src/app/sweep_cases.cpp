#include "sweep_cases.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pcsim/core/error.hpp"

namespace pcsim::app {

namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// The fields of one line; a quoted field keeps its spaces, "" inside is one quote.
std::vector<std::string> split_fields(const std::string& line, const std::string& where,
                                      const std::string& path) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string field;
    if (i < line.size() && line[i] == '"') {
      for (++i;; ++i) {
        if (i >= line.size()) throw InputError(path, "", where + ": a quote is not closed");
        if (line[i] == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else if (line[i] == '"') {
          break;
        } else {
          field += line[i];
        }
      }
      ++i;
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',')
        throw InputError(path, "", where + ": text after a closing quote");
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      field = trimmed(line.substr(i, end - i));
      i = end;
    }
    fields.push_back(field);
    if (i >= line.size()) return fields;
    ++i;  // the comma
  }
}

void read_header(CaseTable& table, const std::vector<std::string>& keys, const std::string& where) {
  for (std::size_t c = 0; c < keys.size(); ++c) {
    const std::string& key = keys[c];
    if (key.empty() || key.find_first_of(" \t=") != std::string::npos)
      throw InputError(table.path, "",
                       where + ", column " + std::to_string(c + 1) + ": '" + key +
                           "' is not a scene key (the header line names one key per column)");
    for (const auto& k : table.columns)
      if (k == key) throw InputError(table.path, key, where + ": the column is given twice");
    table.columns.push_back(key);
  }
}

void read_comment(CaseTable& table, const std::string& line, const std::string& where) {
  const std::string tag = "# sample:";
  if (line.compare(0, tag.size(), tag) != 0) return;
  table.sample = nlohmann::json::parse(line.substr(tag.size()), nullptr, false);
  if (table.sample.is_discarded() || !table.sample.is_object())
    throw InputError(table.path, "", where + ": the '# sample:' comment is not a JSON object");
}

}  // namespace

CaseTable read_case_table(const std::string& path, std::size_t max_rows) {
  CaseTable table;
  table.path = path;
  std::ifstream in(path);
  if (!std::filesystem::is_regular_file(path) || !in)
    throw InputError(path, "", "the case table cannot be read (no such file)");
  std::ostringstream text;
  text << in.rdbuf();
  table.text = text.str();
  std::istringstream lines(table.text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = "line " + std::to_string(number);
    if (trimmed(line).empty()) continue;
    if (trimmed(line)[0] == '#') {
      read_comment(table, trimmed(line), where);
      continue;
    }
    const auto fields = split_fields(line, where, path);
    if (table.columns.empty()) {
      read_header(table, fields, where);
      continue;
    }
    if (fields.size() != table.columns.size())
      throw InputError(path, "",
                       where + " has " + std::to_string(fields.size()) + " field(s), the header " +
                           std::to_string(table.columns.size()) + " (a ragged row)");
    for (std::size_t c = 0; c < fields.size(); ++c)
      if (fields[c].empty()) throw InputError(path, table.columns[c], where + ": no value");
    if (table.rows.size() == max_rows)
      throw InputError(path, "", "more than " + std::to_string(max_rows) + " cases");
    table.rows.push_back(fields);
    table.lines.push_back(number);
  }
  if (table.columns.empty() || table.rows.empty())
    throw InputError(path, "",
                     "no cases: the table needs a header line of scene keys and one line per case");
  return table;
}

}  // namespace pcsim::app
