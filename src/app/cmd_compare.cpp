// `pcsim compare RUN_A RUN_B [RUN ...] [--measurement FILE.csv] [-o DIR]`: run
// results side by side, or runs against a measured contact force. The work is
// postproc/compare.py's; this file checks the inputs, owns the output folder
// (output/output_dir.hpp: written into DIR.partial, renamed when complete, removed
// on a failure) and prints the table.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/provenance.hpp"
#include "processes.hpp"

namespace {

using namespace pcsim;
namespace fs = std::filesystem;

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// Why 'folder' is not a `pcsim run` result ("" if it is).
std::string not_a_run_result(const std::string& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) return "not found";
  if (!fs::is_directory(folder, ec))
    return ends_with(folder, ".csv")
               ? "a file, not a run result folder (a measurement is given with --measurement)"
               : "a file, not a pcsim run result folder";
  for (const char* name : {"summary.json", "results.h5"})
    if (!fs::is_regular_file(fs::path(folder) / name, ec))
      return std::string("not a pcsim run result folder: it has no ") + name;
  return "";
}

// The folders and the measurement file compared.
std::vector<std::string> compared(const app::CommandContext& ctx) {
  std::vector<std::string> inputs = ctx.operands;
  if (ctx.has_option("--measurement")) inputs.push_back(ctx.options.at("--measurement"));
  return inputs;
}

// Throws InputError (exit 2) naming the input that cannot be compared.
void check_inputs(const app::CommandContext& ctx) {
  if (ctx.size > 1)
    throw InputError("command line", "", "pcsim compare runs on one rank: start it without mpirun");
  const bool measured = ctx.has_option("--measurement");
  if (ctx.operands.empty() || (ctx.operands.size() < 2 && !measured))
    throw InputError("command line", "",
                     "pcsim compare needs two run result folders, or one and --measurement "
                     "FILE.csv (pcsim compare --help)");
  for (const auto& run : ctx.operands)
    if (const std::string why = not_a_run_result(run); !why.empty()) throw InputError(run, "", why);
  if (measured) {
    const std::string& file = ctx.options.at("--measurement");
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      throw InputError(file, "", fs::exists(file, ec) ? "not a file" : "not found");
  }
}

// out/compare-<A>-<B>...: the names of the folders and of the measurement file.
std::string default_folder(const app::CommandContext& ctx) {
  std::string dir = "out/compare";
  for (const auto& input : compared(ctx)) {
    fs::path name = fs::path(input).lexically_normal();
    if (!name.has_filename()) name = name.parent_path();
    dir += "-" + (ends_with(input, ".csv") ? name.stem() : name.filename()).string();
  }
  return dir;
}

// Why the comparison may not go to 'dir' ("" if it may): it is or holds one of
// the inputs, or it is the result of another pcsim command.
std::string output_refusal(const app::CommandContext& ctx, const std::string& dir) {
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(fs::absolute(dir), ec);
  for (const auto& input : compared(ctx)) {
    const fs::path path = fs::weakly_canonical(fs::absolute(input), ec);
    const auto [end, rest] = std::mismatch(target.begin(), target.end(), path.begin(), path.end());
    if (end == target.end()) return "'" + dir + "' is or holds " + input + ", an input";
  }
  std::ifstream manifest(fs::path(dir) / output::OutputDir::kManifestName);
  if (!manifest) return "";
  const auto recorded = nlohmann::json::parse(manifest, nullptr, false);
  const std::string command =
      recorded.is_object() ? recorded.value("command", std::string("?")) : std::string("?");
  if (command == "compare") return "";
  return "'" + dir + "' holds the result of pcsim " + command +
         ", not of pcsim compare: give another folder with -o";
}

output::OutputRequest output_request(const app::CommandContext& ctx) {
  output::OutputRequest request;
  request.dir = ctx.output_dir.empty() ? default_folder(ctx) : ctx.output_dir;
  request.given_in = "command line";
  request.given_by = ctx.output_dir.empty() ? "default output folder" : "-o";
  request.command = "compare";
  request.scene_file = ctx.operands.front();
  request.scene_name = fs::path(request.dir).filename().string();
  output::ProvenanceInputs provenance;
  provenance.command = "compare";
  provenance.arguments = ctx.arguments;
  provenance.scene_file = ctx.operands.front();
  provenance.ranks = ctx.size;
  request.provenance = output::make_provenance(provenance);
  if (const std::string why = output_refusal(ctx, request.dir); !why.empty())
    throw InputError(request.given_in, request.given_by, why);
  return request;
}

// The script's one-line message without its "compare.py failed (exit 2): compare.py: error: ".
std::string script_message(const std::string& why) {
  const std::string marker = "error: ";
  const auto at = why.rfind(marker);
  return at == std::string::npos ? why : why.substr(at + marker.size());
}

int compare(const app::CommandContext& ctx) {
  check_inputs(ctx);
  output::OutputDir out(ctx.comm, output_request(ctx));
  std::vector<std::string> args = {"-o", out.partial_dir()};
  args.insert(args.end(), ctx.operands.begin(), ctx.operands.end());
  if (ctx.has_option("--measurement"))
    args.insert(args.end(), {"--measurement", ctx.options.at("--measurement")});
  if (ctx.has_option("--max-lag"))
    args.insert(args.end(), {"--max-lag", ctx.options.at("--max-lag")});
  int status = 0;
  const std::string why = app::run_postproc("compare.py", args, &status);
  if (status == app::kPostprocWriteFailed) throw OutputError(out.final_dir(), script_message(why));
  if (status == app::kExitInput) {  // the partial folder goes with 'out'
    std::fprintf(stderr, "pcsim: error: %s\n", script_message(why).c_str());
    return app::kExitInput;
  }
  if (!why.empty()) throw std::runtime_error(why);
  out.commit();
  std::ifstream table(fs::path(out.final_dir()) / "compare.md");
  const std::string text((std::istreambuf_iterator<char>(table)), std::istreambuf_iterator<char>());
  std::printf("%s\npcsim compare: wrote %s (report.html, compare.csv, compare.md, plots)\n",
              text.c_str(), out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("compare", "run results side by side, or a run against a measurement", compare);
PCSIM_COMMAND_OPERANDS(compare, "compare", "RUN_A [RUN_B ...]");
PCSIM_COMMAND_HELP(
    compare, "compare",
    "Two runs or more, or one run or more and --measurement FILE.csv.\n"
    "RUN_A, RUN_B, ...: result folders of pcsim run (summary.json, results.h5). The first is the\n"
    "reference: every other run, and the measurement, gets its difference from it. Pantographs\n"
    "are matched by name (any names when every run has one). A measurement (CSV: contact forces\n"
    "by position, or by time with a speed, units in the header; one force column per pantograph,\n"
    "'force NAME [N]') is filtered like RUN_A (its analysis.cutoff_hz) and aligned to RUN_A's\n"
    "pantographs by cross-correlation, one lag for the file; the lag and each pantograph's force\n"
    "offset are reported.\n"
    "results: compare.csv and compare.md (the EN 50318 figures of every pantograph side by side,\n"
    "differences absolute and in %), compare.json, force_uplift.png (force by position, one\n"
    "panel per pantograph, and the uplift at the supports), spectra.png, inputs.diff (the\n"
    "composed scene, design and pantograph models that differ), span_extremes.csv (runs on the\n"
    "same supports: each run's largest and smallest force per span, and where its actual\n"
    "maximum and minimum fall, in compare.md too), report.html.\n"
    "Bad input (a folder that is no run result, a missing file, a CSV without units): one\n"
    "message, exit 2, no folder. Docs: docs/assessment.md \"Comparing results: pcsim compare\".\n",
    {"--measurement", "FILE.csv", "a measured contact force to compare with RUN_A (format: docs)"},
    {"--max-lag", "M",
     "largest position lag of the measurement searched (m; default half a span)"});
