#include "rerun.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "pcsim/core/version.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"

namespace fs = std::filesystem;

namespace pcsim::app {

namespace {

std::string summary_path(const std::string& dir) {
  return (fs::path(dir) / "summary.json").string();
}

// DIR's provenance, or null with the reason in 'why'.
nlohmann::json read_provenance(const std::string& dir, std::string& why) {
  std::ifstream in(summary_path(dir));
  if (!in) {
    why = "'" + dir + "' holds no summary.json (give the folder of a pcsim run result)";
    return nullptr;
  }
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  if (!summary.is_object() || !summary.contains("provenance") ||
      !summary["provenance"].contains("inputs")) {
    why = summary_path(dir) + " records no inputs (written by a pcsim before records existed)";
    return nullptr;
  }
  return summary["provenance"];
}

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

}  // namespace

std::string prepare_rerun(const std::string& dir, CommandContext& ctx,
                          std::vector<std::string>& petsc_arguments) {
  std::string why;
  const auto p = read_provenance(dir, why);
  if (p.is_null()) return why;
  if (p.value("command", std::string()) != "run")
    return summary_path(dir) + " is the record of a 'pcsim " + p.value("command", std::string()) +
           "', not of a run";
  if (!ctx.scene_path.empty()) return "--rerun takes the scene from the record: give no scene";
  fs::path scene = p.value("scene_file", std::string());
  if (scene.is_relative() && !fs::exists(scene))
    scene = fs::path(p.value("working_directory", std::string())) / scene;
  ctx.scene_path = scene.string();
  ctx.overrides = p.value("overrides", std::vector<std::string>());
  const auto recorded = words(p.value("petsc_options", std::string()));
  petsc_arguments.insert(petsc_arguments.begin(), recorded.begin(), recorded.end());
  if (ctx.output_dir.empty()) ctx.output_dir = fs::path(dir).lexically_normal().string() + "-rerun";
  return "";
}

void check_rerun(const CommandContext& ctx, const scene::InputNode& scene) {
  const std::string dir = ctx.options.at("--rerun");
  std::string why;
  const auto p = read_provenance(dir, why);
  if (p.is_null()) throw InputError("command line", "--rerun", why);
  const auto now = simulation::recorded_inputs(ctx.scene_path, scene);
  for (const auto& was : p["inputs"]) {
    const std::string role = was.value("role", std::string());
    const auto match =
        std::find_if(now.begin(), now.end(), [&](const auto& f) { return f.role == role; });
    if (match == now.end() || match->sha256 != was.value("sha256", std::string()))
      throw InputError(summary_path(dir), "provenance.inputs",
                       "the " + role + " file '" + was.value("path", std::string()) +
                           "' no longer reads as it did for that result (SHA-256 " +
                           was.value("sha256", std::string()).substr(0, 12) +
                           "...); its recorded content is in the record's 'content'");
  }
  std::vector<std::string> warnings;
  if (p.value("git_commit", std::string()) != git_commit() ||
      p.value("pcsim_version", std::string()) != version())
    warnings.push_back(summary_path(dir) + ": made by pcsim " +
                       p.value("pcsim_version", std::string("?")) + " (git " +
                       p.value("git_commit", std::string("?")) + "), this is " + version() +
                       " (git " + git_commit() + "): the figures may differ");
  if (p.value("ranks", 1) != ctx.size)
    warnings.push_back(summary_path(dir) + ": made on " + std::to_string(p.value("ranks", 1)) +
                       " rank(s), this run has " + std::to_string(ctx.size) +
                       ": the figures agree to round-off only");
  print_warnings(ctx, warnings);
}

}  // namespace pcsim::app
