// `pcsim sweep SCENE --set KEY=A:B:STEP [--set KEY=V1,V2,...] [--set KEY=VALUE] [-j N]`:
// a run scene for every combination of the swept values, each case its own
// `pcsim run` process (up to N at a time), one table of the EN 50318 figures
// (output/sweep_results.hpp), plots against the swept values and a report.
// `pcsim sweep SCENE --cases FILE.csv`: the cases are the rows of a table
// (sweep_cases.hpp, e.g. a sample of postproc/sample.py), not a grid.
#include <petscsys.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/output/sweep_journal.hpp"
#include "pcsim/output/sweep_results.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"
#include "pcsim/solvers/command_line.hpp"
#include "processes.hpp"
#include "sweep_bases.hpp"
#include "sweep_cases.hpp"
#include "sweep_mpi.hpp"
#include "sweep_runner.hpp"

namespace {

using namespace pcsim;
using app::CommandContext;

using Plan = app::SweepPlan;

constexpr std::size_t kMaxCases = 10000;

std::string number_text(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.10g", v);
  return s;
}

// "A:B:STEP" (B included) or "V1,V2,..." -> the values; none for a plain value.
std::vector<std::string> expand(const std::string& assignment) {
  const std::string key = assignment.substr(0, assignment.find('='));
  const std::string text = assignment.substr(assignment.find('=') + 1);
  const std::string label = "command line --set " + assignment;
  const std::string flow_openers = "[{}]";  // a YAML list or map: one value (balanced braces)
  if (text.empty() || flow_openers.find(text[0]) < 2) return {};
  std::vector<std::string> parts;
  std::size_t start = 0;
  const char sep = text.find(':') != std::string::npos ? ':' : ',';
  for (std::size_t end; (end = text.find(sep, start)) != std::string::npos; start = end + 1)
    parts.push_back(text.substr(start, end - start));
  parts.push_back(text.substr(start));
  if (parts.size() < 2) return {};
  if (sep == ',') return parts;
  double v[3];
  for (std::size_t i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = i < parts.size() ? std::strtod(parts[i].c_str(), &end) : 0;
    if (parts.size() != 3 || end == parts[i].c_str() || *end != '\0')
      throw InputError(label, key, "a range is FROM:TO:STEP with three numbers");
  }
  if (!(v[2] > 0) || v[1] < v[0] || (v[1] - v[0]) / v[2] > 1000)
    throw InputError(label, key, "a range needs FROM <= TO, STEP > 0 and at most 1000 values");
  std::vector<std::string> values;
  for (long k = 0; v[0] + k * v[2] <= v[1] + 1e-9 * v[2]; ++k)
    values.push_back(number_text(v[0] + k * v[2]));
  return values;
}

std::string folder_safe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '+') c = '_';
  return s;
}

// The case's number, 1-based, zero-padded to width.
std::string case_index(std::size_t k, int width) {
  char index[24];
  std::snprintf(index, sizeof index, "%0*zu", width, k + 1);
  return index;
}

// The grid of the swept --set values: every combination, the first key varying slowest.
void plan_grid(Plan& plan) {
  std::size_t count = 1;
  for (const auto& s : plan.swept) count *= s.values.size();
  if (count > kMaxCases)
    throw InputError("command line", "--set",
                     std::to_string(count) + " cases: at most " + std::to_string(kMaxCases));
  for (std::size_t k = 0; k < count; ++k) {
    output::SweepCase c;
    std::vector<std::string> assignments;
    c.name = case_index(k, count >= 100 ? 3 : 2);
    std::size_t rest = k, stride = count;
    for (const auto& s : plan.swept) {
      stride /= s.values.size();
      const std::string& value = s.values[rest / stride];
      rest %= stride;
      c.values.emplace_back(s.key, value);
      assignments.push_back(s.key + "=" + value);
      c.name += "_" + folder_safe(s.key.substr(s.key.find_last_of('.') + 1) + "-" + value);
    }
    plan.cases.push_back(c);
    plan.assignments.push_back(assignments);
  }
}

// The rows of a case table (--cases), each a case; the swept values of a
// key are its values in the order they first appear.
void plan_table(Plan& plan, const app::CaseTable& table) {
  for (const auto& key : table.columns) plan.swept.push_back({key, "", {}});
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    output::SweepCase c;
    const std::size_t count = table.rows.size();
    c.name = case_index(k, count >= 1000 ? 4 : count >= 100 ? 3 : 2);
    std::vector<std::string> assignments;
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const std::string& value = table.rows[k][i];
      auto& values = plan.swept[i].values;
      if (std::find(values.begin(), values.end(), value) == values.end()) values.push_back(value);
      c.values.emplace_back(table.columns[i], value);
      assignments.push_back(table.columns[i] + "=" + value);
    }
    plan.cases.push_back(c);
    plan.assignments.push_back(assignments);
    plan.origins.push_back(table.path + " line " + std::to_string(table.lines[k]));
  }
  plan.table = {{"file", table.path},
                {"columns", table.columns},
                {"rows", table.rows.size()},
                {"lines", table.lines}};
  plan.sample = table.sample;
  plan.table_text = table.text;
}

Plan make_plan(const CommandContext& ctx) {
  Plan plan;
  for (const auto& o : ctx.overrides) {
    if (o.find('=') == std::string::npos)
      pcsim::scene::parse_override(o, {"", "command line --set " + o});
    auto values = expand(o);
    if (values.empty())
      plan.fixed.push_back(o);
    else
      plan.swept.push_back({o.substr(0, o.find('=')), o, std::move(values)});
  }
  if (ctx.has_option("--cases")) {
    if (!plan.swept.empty())
      throw InputError("command line", "--cases",
                       "the cases come from " + ctx.options.at("--cases") + ": --set " +
                           plan.swept[0].given + " cannot sweep too (give plain --set KEY=VALUE)");
    const app::CaseTable table = app::read_case_table(ctx.options.at("--cases"), kMaxCases);
    plan_table(plan, table);
    return plan;
  }
  if (plan.swept.empty())
    throw InputError("command line", "--set",
                     "a sweep needs a range KEY=FROM:TO:STEP, a list KEY=V1,V2,... "
                     "(e.g. --set simulation.speed_kmh=200:400:20) or --cases FILE.csv");
  plan_grid(plan);
  return plan;
}

// Every case read and checked as `pcsim run` would (inputs.hpp: input errors
// before anything runs; a command-line option that one case refuses, e.g.
// -ts_max_time past a faster case's end, has that case named); the modal
// bases they need.
app::SweepBases check_cases(const CommandContext& ctx, const Plan& plan) {
  solvers::read_time_integration_options(ctx.comm);  // their own errors: no case to name
  app::SweepBases bases;
  std::vector<scene::InputOverride> fixed;
  for (const auto& o : plan.fixed)
    fixed.push_back(scene::parse_override(o, {"", "command line --set " + o}));
  for (std::size_t k = 0; k < plan.cases.size(); ++k) {
    auto overrides = fixed;
    for (std::size_t i = 0; i < plan.swept.size(); ++i) {
      const std::string origin =
          plan.origins.empty() ? "command line --set " + plan.swept[i].given : plan.origins[k];
      overrides.push_back(scene::parse_override(
          plan.assignments[k][i], {"", origin + " (case " + plan.cases[k].name + ")"}));
    }
    const scene::InputNode composed = scene::load_composed(ctx.scene_path, overrides);
    try {
      const auto inputs = app::read_run_inputs(ctx, composed);
      bases.add(ctx, inputs.run, inputs.memory.dofs);
    } catch (const InputError& e) {  // a command-line option that this case refuses
      if (e.file() != "command line") throw;
      throw InputError(e.file(), e.key(), e.reason() + " (case " + plan.cases[k].name + ")");
    }
  }
  return bases;
}

// Plots of the figures against the swept values and report.html (warnings only).
void write_plots_and_report(const CommandContext& ctx, const output::OutputDir& out) {
  for (const auto& [script, args] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"sweep_plots.py", {out.partial_dir()}}, {"report.py", {"sweep", out.partial_dir()}}}) {
    if (script == "report.py" && ctx.has_option("--no-report")) continue;
    const std::string why = app::run_postproc(script, args);
    if (!why.empty()) std::fprintf(stderr, "pcsim: warning: %s\n", why.c_str());
  }
}

int positive_option(const CommandContext& ctx, const std::string& name) {
  if (!ctx.has_option(name)) return 1;
  char* end = nullptr;
  const long v = std::strtol(ctx.options.at(name).c_str(), &end, 10);
  if (*end != '\0' || v < 1 || v > 256)
    throw InputError("command line", name, "must be a whole number from 1 to 256");
  return static_cast<int>(v);
}

// The sweep's definition: the SHA-256 over the scene and every file it reads
// (with the shared --set), the --set as given (swept values), the case table
// and the PETSc options of the cases (command line and PETSC_OPTIONS). The
// journal keeps it: a rerun resumes only the same definition.
std::string sweep_definition(const CommandContext& ctx, const Plan& plan,
                             const scene::InputNode& scene) {
  std::string definition = "sweep";
  for (const auto& o : ctx.overrides) definition += " --set " + o;
  if (plan.table.is_object()) definition += " --cases " + plan.table_text;
  definition += "\npetsc:";
  for (const auto& a : ctx.petsc_arguments) definition += " " + a;
  const char* environment = std::getenv("PETSC_OPTIONS");
  definition += std::string("\nPETSC_OPTIONS=") + (environment ? environment : "");
  return simulation::inputs_fingerprint(definition,
                                        simulation::recorded_inputs(ctx.scene_path, scene));
}

// The output folder's request; a leftover partial folder of the same
// definition is resumed (sweep_runner.hpp).
output::OutputRequest sweep_request(const CommandContext& ctx, const Plan& plan,
                                    const scene::InputNode& scene, const std::string& definition) {
  // The scene with the overrides every case shares names the sweep; the
  // provenance lists every --set as given.
  CommandContext shared = ctx;
  shared.overrides = plan.fixed;
  output::OutputRequest request = shared.output_request(scene);
  request.provenance["overrides"] = ctx.overrides;
  std::string fingerprinted = "sweep";  // the fingerprint covers the swept values too
  for (const auto& o : ctx.overrides) fingerprinted += " --set " + o;
  if (plan.table.is_object()) fingerprinted += " --cases " + plan.table_text;
  request.provenance["inputs_fingerprint"] = simulation::inputs_fingerprint(
      fingerprinted, simulation::recorded_inputs(ctx.scene_path, scene));
  if (ctx.output_dir.empty()) request.dir += "-sweep";
  const bool overwrite = ctx.overwrite;
  request.leftover = [definition, overwrite](const std::string& partial, std::string& why) {
    return app::sweep_leftover(partial, definition, overwrite, why);
  };
  return request;
}

// The sweep's command line without -sweep_ranks_per_case: how the ranks are
// grouped is no part of the sweep's definition, nor an option of its cases.
CommandContext without_ranks_per_case(const CommandContext& ctx) {
  CommandContext stripped = ctx;
  auto& args = stripped.petsc_arguments;
  for (std::size_t i = 0; i < args.size(); ++i)
    if (args[i] == app::kRanksPerCaseOption) {
      const bool valued =
          i + 1 < args.size() && (args[i + 1][0] != '-' || args[i + 1].size() == 1 ||
                                  std::isdigit(static_cast<unsigned char>(args[i + 1][1])));
      args.erase(args.begin() + static_cast<long>(i),
                 args.begin() + static_cast<long>(i + (valued ? 2 : 1)));
      break;
    }
  return stripped;
}

// Under mpirun: -j and --ranks are the local mode's; the journal is opened on
// rank 0 and the cases it holds are known to every rank; no accuracy pilot
// per case unless asked for (as the local mode's case_command).
std::size_t open_mpi_sweep(const CommandContext& ctx, Plan& plan, const output::OutputDir& out,
                           const std::string& definition) {
  std::size_t resumed = 0;
  app::on_rank0(ctx, [&] { resumed = app::open_sweep_journal(plan, out, definition); });
  std::vector<int> statuses;
  for (const auto& c : plan.cases) statuses.push_back(c.status);
  MPI_Bcast(statuses.data(), static_cast<int>(statuses.size()), MPI_INT, 0, ctx.comm);
  for (std::size_t k = 0; k < plan.cases.size(); ++k) plan.cases[k].status = statuses[k];
  unsigned long count = resumed;
  MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, ctx.comm);
  if (std::find(ctx.petsc_arguments.begin(), ctx.petsc_arguments.end(), "-pcsim_accuracy_pilot") ==
      ctx.petsc_arguments.end())
    PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-pcsim_accuracy_pilot", "false"));
  return count;
}

void refuse_local_options_under_mpirun(const CommandContext& ctx) {
  for (const char* name : {"-j", "--ranks"})
    if (ctx.has_option(name))
      throw InputError("command line", name,
                       "under mpirun every rank runs cases, " +
                           std::string(app::kRanksPerCaseOption) +
                           " K ranks each (docs/cluster.md): -j and --ranks are for a sweep "
                           "without mpirun");
}

// The tables from the journal (rank 0), plots and report, the folder committed;
// the exit status is the worst of the cases'.
int finish_sweep(const CommandContext& ctx, Plan& plan, output::OutputDir& out) {
  std::vector<std::pair<std::string, std::vector<std::string>>> swept;
  for (const auto& s : plan.swept) swept.emplace_back(s.key, s.values);
  nlohmann::json record = nlohmann::json::object();
  if (plan.table.is_object()) record = {{"cases_table", plan.table}, {"sample", plan.sample}};
  app::on_rank0(ctx, [&] {
    if (ctx.size > 1) app::fill_cases_from_journal(plan, out);
    const std::string table = output::write_sweep_results(out, swept, plan.cases, record);
    app::print0(ctx, "\n%s\n", table.c_str());
    write_plots_and_report(ctx, out);
  });
  int status = 0;
  for (const auto& c : plan.cases) status = std::max(status, c.status);
  MPI_Bcast(&status, 1, MPI_INT, 0, ctx.comm);
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return status == 0 ? 0 : std::min(status, app::kExitInternal);
}

int run_sweep(const CommandContext& given) {
  const int ranks_per_case = app::sweep_ranks_per_case(given);
  const CommandContext ctx = without_ranks_per_case(given);
  const bool mpi = ctx.size > 1;
  if (mpi) refuse_local_options_under_mpirun(ctx);
  const int jobs = positive_option(ctx, "-j");
  positive_option(ctx, "--ranks");
  Plan plan = make_plan(ctx);
  const app::SweepBases bases = check_cases(ctx, plan);
  CommandContext shared = ctx;
  shared.overrides = plan.fixed;
  const scene::InputNode scene = shared.load_scene();
  const std::string definition = sweep_definition(ctx, plan, scene);
  output::OutputDir out(ctx.comm, sweep_request(ctx, plan, scene, definition));
  const std::size_t resumed = mpi ? open_mpi_sweep(ctx, plan, out, definition)
                                  : app::open_sweep_journal(plan, out, definition);
  if (mpi)
    app::print0(ctx, "pcsim sweep: scene '%s', %zu cases, %d group(s) of %d rank(s)\n",
                ctx.scene_name(scene).c_str(), plan.cases.size(), ctx.size / ranks_per_case,
                ranks_per_case);
  else
    app::print0(ctx, "pcsim sweep: scene '%s', %zu cases, %d at a time\n",
                ctx.scene_name(scene).c_str(), plan.cases.size(), jobs);
  app::print0(ctx, "%s", bases.summary().c_str());
  if (out.resumed())
    app::print0(ctx, "  resumed %s: %zu case(s) finished (journal kept), %zu to run\n",
                out.partial_dir().c_str(), resumed, plan.cases.size() - resumed);
  if (const int signal_number = mpi ? app::run_sweep_cases_mpi(ctx, plan, out, ranks_per_case)
                                    : app::run_sweep_cases(ctx, plan, out, jobs)) {
    out.keep_partial();
    app::print0(ctx,
                "\n  interrupted (%s): the finished cases (in %s) and the stopped ones are in "
                "%s/cases/; the same command again resumes the sweep\n",
                simulation::signal_name(signal_number), output::kSweepJournalName,
                out.partial_dir().c_str());
    return 128 + signal_number;
  }
  return finish_sweep(ctx, plan, out);
}

}  // namespace

PCSIM_COMMAND_HELP(
    sweep_help, "sweep",
    "Runs a run scene (docs/scene-format.md, \"Run scenes\") for every combination of\n"
    "the values of the swept keys, or for every row of a case table (docs/studies.md:\n"
    "sampling designs, sensitivity), each case as `pcsim run` with its --set:\n"
    "  --set KEY=FROM:TO:STEP   a range (TO included), e.g. simulation.speed_kmh=200:400:20\n"
    "  --set KEY=V1,V2,...      a list of values, e.g. pantographs[0].start=static,ramp\n"
    "  --set KEY=VALUE          the same value in every case\n"
    "  --cases FILE.csv         the cases as the rows of a table: a header line of keys,\n"
    "                           one line of values per case ('#' lines are comments; a\n"
    "                           '# sample: {...}' line, as postproc/sample.py writes, is\n"
    "                           kept in summary.json); no ranges or lists with it\n"
    "PETSc options go to every case (no accuracy pilot unless -pcsim_accuracy_pilot true).\n"
    "Results in -o DIR, by default out/<scene name>-sweep/ (<scene name>: the scene's\n"
    "'name', else its file name without .yaml): cases/<case>/ (a run result each, and\n"
    "its log), journal.jsonl (one line per finished case, written as it finishes),\n"
    "sweep.csv and sweep.md (the EN 50318 figures of every case with their verdicts,\n"
    "from the journal), sweep.png (figures against the swept values with the\n"
    "acceptance ranges), summary.json, report.html. A failed case is recorded and the\n"
    "sweep goes on; the exit status is the worst of the cases'. SIGINT/SIGTERM stop\n"
    "the running cases (130/143, the sweep left in DIR.partial); the same command again\n"
    "resumes it (finished cases kept), another sweep into it is refused (--overwrite:\n"
    "start anew). sweep.h5: the table with a unit on every column.\n"
    "Under mpirun with more than one rank (docs/cluster.md) the cases run in-process:\n"
    "the ranks are split into groups of -sweep_ranks_per_case K (1; a divisor of the\n"
    "ranks), each group runs one case at a time on its K ranks, taking the next case\n"
    "as it finishes one; each group journals into journal-<group>.jsonl, merged into\n"
    "journal.jsonl by rank 0. `mpirun -n 1` is a sweep without mpirun (-j, --ranks).\n",
    {"-j", "N", "run up to N cases at a time (1)"},
    {"--ranks", "N", "MPI ranks of each case (1; through mpiexec)"},
    {"--cases", "FILE.csv", "the cases: one row of a table each (see above)"},
    {"--no-report", "", "no report.html"});
PCSIM_COMMAND("sweep",
              "a run scene over ranges of values or a case table: table, plots and report of "
              "EN 50318",
              run_sweep);
