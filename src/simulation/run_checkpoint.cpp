#include "pcsim/simulation/run_checkpoint.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "pcsim/core/error.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/output/checkpoint.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/criteria_reader.hpp"
#include "pcsim/simulation/context.hpp"

namespace fs = std::filesystem;

namespace pcsim::simulation {

namespace {

std::string sha256_hex(const std::string& text) {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> md(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(md.get(), EVP_sha256(), nullptr);
  EVP_DigestUpdate(md.get(), text.data(), text.size());
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(md.get(), digest, &length);
  std::string hex;
  char byte[3];
  for (unsigned int i = 0; i < length; ++i) {
    std::snprintf(byte, sizeof byte, "%02x", digest[i]);
    hex += byte;
  }
  return hex;
}

nlohmann::json inputs_json(const std::vector<InputFile>& inputs) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& f : inputs)
    j.push_back({{"role", f.role}, {"path", f.path}, {"sha256", f.sha256}});
  return j;
}

std::vector<InputFile> inputs_from(const nlohmann::json& j) {
  std::vector<InputFile> inputs;
  for (const auto& f : j) inputs.push_back({f.at("role"), f.at("path"), f.at("sha256")});
  return inputs;
}

std::string term_array(std::size_t k) {
  return "/terms/" + std::to_string(k);
}

// Everything but the state vectors, as JSON (doubles round-trip exactly).
nlohmann::json scalars_json(const RunCheckpoint& c) {
  const auto& s = c.state;
  return {{"t", s.t},
          {"step", s.step},
          {"time_step", s.time_step},
          {"user_time_step", s.user_time_step},
          {"accepted_since_cut", s.accepted_since_cut},
          {"has_reference", s.has_reference},
          {"reference_t", s.reference_t},
          {"shift_v", s.shift_v},
          {"shift_a", s.shift_a},
          {"has_alpha_term", s.has_alpha_term},
          {"terms", s.terms},
          {"head_offsets", s.head_offsets},
          {"records", c.progress.records},
          {"snapshots", c.progress.snapshots},
          {"newton_iterations", c.progress.newton_iterations},
          {"rejected_steps", c.progress.rejected_steps},
          {"wall_time_s", c.progress.wall_time_s},
          {"path", c.path},
          {"ranks", c.ranks},
          {"modal_cutoff_hz", c.modal_cutoff_hz},
          {"window_shifts", c.window_shifts},
          {"inputs", inputs_json(c.inputs)}};
}

void from_scalars_json(const nlohmann::json& j, RunCheckpoint& c) {
  auto& s = c.state;
  s.t = j.at("t");
  s.step = j.at("step");
  s.time_step = j.at("time_step");
  s.user_time_step = j.at("user_time_step");
  s.accepted_since_cut = j.at("accepted_since_cut");
  s.has_reference = j.at("has_reference");
  s.reference_t = j.at("reference_t");
  s.shift_v = j.at("shift_v");
  s.shift_a = j.at("shift_a");
  s.has_alpha_term = j.value("has_alpha_term", false);  // absent before it was kept
  s.terms = j.at("terms").get<std::vector<std::vector<double>>>();
  s.head_offsets = j.at("head_offsets").get<std::vector<double>>();
  c.progress.records = j.at("records");
  c.progress.snapshots = j.at("snapshots");
  c.progress.newton_iterations = j.at("newton_iterations");
  c.progress.rejected_steps = j.at("rejected_steps");
  c.progress.wall_time_s = j.at("wall_time_s");
  c.path = j.at("path");
  c.ranks = j.at("ranks");
  c.inputs = inputs_from(j.at("inputs"));
  c.modal_cutoff_hz = j.value("modal_cutoff_hz", 0.0);  // absent before it was kept
  c.window_shifts = j.value("window_shifts", -1);       // absent before windows restarted
}

output::CheckpointData to_data(const RunCheckpoint& c) {
  output::CheckpointData d;
  const auto& s = c.state;
  d.arrays = {{"/state/U", s.U}, {"/state/V", s.V}, {"/state/A", s.A}};
  if (s.has_reference) {
    d.arrays["/reference/U"] = s.reference_U;
    d.arrays["/reference/V"] = s.reference_V;
    d.arrays["/reference/A"] = s.reference_A;
  }
  if (s.has_alpha_term) d.arrays["/alpha_term"] = s.alpha_term;
  for (std::size_t k = 0; k < s.terms.size(); ++k) d.arrays[term_array(k)] = s.terms[k];
  d.arrays["/pantographs/head_offset"] = s.head_offsets;
  nlohmann::json j = scalars_json(c);
  j.erase("terms");
  j.erase("head_offsets");
  j.erase("inputs");
  for (const auto& [key, value] : j.items()) {
    if (value.is_string())
      d.texts[key] = value.get<std::string>();
    else
      d.numbers[key] = value.is_boolean() ? (value.get<bool>() ? 1.0 : 0.0) : value.get<double>();
  }
  d.numbers["term_count"] = static_cast<double>(s.terms.size());
  d.texts["inputs"] = inputs_json(c.inputs).dump();
  return d;
}

RunCheckpoint from_data(output::CheckpointData& d) {
  nlohmann::json j;
  for (const auto& [key, value] : d.numbers) j[key] = value;
  for (const auto& [key, value] : d.texts) j[key] = value;
  j["has_reference"] = d.numbers.at("has_reference") != 0;
  j["has_alpha_term"] = d.numbers.count("has_alpha_term") && d.numbers.at("has_alpha_term") != 0;
  for (const char* key : {"step", "accepted_since_cut", "records", "snapshots", "newton_iterations",
                          "rejected_steps", "ranks"})
    j[key] = static_cast<long>(d.numbers.at(key));
  if (d.numbers.count("window_shifts")) {  // not a whole number: damaged (below)
    const double shifts = d.numbers.at("window_shifts");
    j["window_shifts"] = std::isfinite(shifts) && shifts == std::floor(shifts) && shifts < 1e9
                             ? static_cast<long>(shifts)
                             : -2L;
  }
  j["inputs"] = nlohmann::json::parse(d.texts.at("inputs"));
  j["head_offsets"] = d.arrays.at("/pantographs/head_offset");
  j["terms"] = nlohmann::json::array();
  for (std::size_t k = 0; k < static_cast<std::size_t>(d.numbers.at("term_count")); ++k)
    j["terms"].push_back(d.arrays.at(term_array(k)));
  RunCheckpoint c;
  from_scalars_json(j, c);
  c.state.U = std::move(d.arrays.at("/state/U"));
  c.state.V = std::move(d.arrays.at("/state/V"));
  c.state.A = std::move(d.arrays.at("/state/A"));
  if (c.state.has_reference) {
    c.state.reference_U = std::move(d.arrays.at("/reference/U"));
    c.state.reference_V = std::move(d.arrays.at("/reference/V"));
    c.state.reference_A = std::move(d.arrays.at("/reference/A"));
  }
  if (c.state.has_alpha_term) c.state.alpha_term = std::move(d.arrays.at("/alpha_term"));
  return c;
}

// What is damaged in checkpoint c ("" if nothing): values a run cannot have
// written (non-finite numbers, negative steps or times, vectors of unequal
// lengths), so that a damaged file is bad input (exit 2), not a solver failure.
std::string damage(const RunCheckpoint& c) {
  const auto& s = c.state;
  auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (!std::isfinite(s.t) || s.t < 0)
    return "its time 't' is not a time (" + std::to_string(s.t) + ")";
  if (s.step < 0 || s.accepted_since_cut < 0) return "its step counts are negative";
  if (!(std::isfinite(s.time_step) && s.time_step > 0) ||
      !(std::isfinite(s.user_time_step) && s.user_time_step > 0))
    return "its time step is not positive and finite";
  if (s.U.empty() || s.V.size() != s.U.size() || s.A.size() != s.U.size())
    return "its state vectors U, V, A differ in length";
  if (!finite(s.U) || !finite(s.V) || !finite(s.A)) return "its state holds non-finite values";
  if (s.has_reference &&
      (!std::isfinite(s.reference_t) || !std::isfinite(s.shift_v) || !std::isfinite(s.shift_a) ||
       s.reference_U.size() != s.U.size() || !finite(s.reference_U) || !finite(s.reference_V) ||
       !finite(s.reference_A)))
    return "its reference state (the cheap path's J0) is not finite or not of the state's length";
  if (s.has_alpha_term && (s.alpha_term.size() != s.U.size() || !finite(s.alpha_term)))
    return "its HHT alpha-term is not finite or not of the state's length";
  if (!finite(s.head_offsets)) return "its pantograph head offsets are not finite";
  if (!std::isfinite(c.modal_cutoff_hz) || c.modal_cutoff_hz < 0)
    return "its modal cut-off 'modal_cutoff_hz' is not a frequency";
  if (c.window_shifts < -1) return "its moving window's 'window_shifts' is not a count of shifts";
  for (const auto& t : s.terms)
    if (!finite(t)) return "a term's saved state is not finite";
  return "";
}

// "--set A --set B", or "no --set".
std::string overrides_text(const std::vector<std::string>& overrides) {
  if (overrides.empty()) return "no --set";
  std::string text;
  for (const auto& o : overrides) text += (text.empty() ? "--set " : " --set ") + o;
  return text;
}

}  // namespace

nlohmann::json checkpointed_summary(const std::string& dir) {
  std::ifstream in(dir + "/summary.json");
  auto summary = nlohmann::json::parse(in, nullptr, false);
  return summary.is_discarded() ? nlohmann::json() : summary;
}

namespace {

// Where a scene that differs may come from: the --set overrides of the
// checkpointed run (provenance.overrides of DIR's summary.json) against this
// command's; "" if that summary cannot be read.
std::string overrides_hint(const std::string& dir, const std::vector<std::string>& overrides) {
  std::vector<std::string> were;
  try {
    were =
        checkpointed_summary(dir).at("provenance").at("overrides").get<std::vector<std::string>>();
  } catch (const std::exception&) {
    return "";
  }
  if (were == overrides)
    return " (both runs have " + overrides_text(were) +
           ": the scene file or a base file it names is not what the checkpointed run read)";
  return " (the checkpointed run had " + overrides_text(were) + ", this command has " +
         overrides_text(overrides) + ": give the same --set overrides)";
}

// Why this run cannot continue checkpoint c, read from folder dir ("" if it can).
std::string mismatch(const Context& ctx, const RunCheckpoint& c,
                     const std::vector<InputFile>& inputs, const std::string& dir,
                     const std::vector<std::string>& overrides) {
  if (c.ranks != ctx.size)
    return "the checkpoint was written on " + std::to_string(c.ranks) +
           " rank(s) and this run has " + std::to_string(ctx.size) +
           "; restart on the same number of ranks (mpirun -n " + std::to_string(c.ranks) + ")";
  for (const auto& was : c.inputs) {
    const InputFile* now = nullptr;
    for (const auto& f : inputs)
      if (f.role == was.role) now = &f;
    if (!now || now->sha256 != was.sha256)
      return "the " + was.role + " file " + (now ? "'" + now->path + "' " : "") +
             "(with its base files and overrides) differs from the one the checkpoint was "
             "written with ('" +
             was.path + "', SHA-256 " + was.sha256.substr(0, 12) +
             "...); a restart needs the same scene, design and pantograph models" +
             (was.role == "scene" ? overrides_hint(dir, overrides) : "");
  }
  if (c.inputs.size() != inputs.size())
    return "the scene has other input files than the checkpointed run";
  return "";
}

}  // namespace

std::vector<InputFile> run_input_files(const std::string& scene_path,
                                       const scene::InputNode& scene) {
  const scene::InputNode catenary = scene["catenary"];
  std::vector<InputFile> files = {{"scene", scene_path, sha256_hex(scene::to_yaml(scene))},
                                  {"design", catenary.path_value("design"),
                                   sha256_hex(scene::to_yaml(catenary.load_referenced("design")))}};
  const scene::InputNode list = scene["pantographs"];
  for (std::size_t i = 0; i < list.size(); ++i)
    files.push_back({"pantograph model " + std::to_string(i + 1), list.at(i).path_value("model"),
                     sha256_hex(scene::to_yaml(list.at(i).load_referenced("model")))});
  // A criteria set the scene names by its file (not a built-in set: those are pcsim's).
  if (scene.has("assessment") && scene["assessment"].has("criteria")) {
    const scene::InputNode a = scene["assessment"];
    const auto builtin = scene::builtin_criteria_sets();
    if (std::find(builtin.begin(), builtin.end(), a.get_string("criteria")) == builtin.end())
      files.push_back(
          {"criteria set", a.path_value("criteria"),
           sha256_hex(scene::to_yaml(scene::InputNode::load_file(a.path_value("criteria"))))});
  }
  return files;
}

namespace {

// Files named by the reference keys below 'node' (key path 'path'), recursively.
void add_referenced(const scene::InputNode& node, const std::string& path,
                    std::vector<RecordedInput>& out) {
  if (node.is_sequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      add_referenced(node.at(i), path + "[" + std::to_string(i) + "]", out);
    return;
  }
  if (!node.is_map()) return;
  for (const auto& key : node.keys()) {
    const std::string child = path.empty() ? key : path + "." + key;
    const bool reference =
        key == "design" || key == "model" || key == "rigid_model" || key == "criteria";
    if (reference && node[key].is_scalar()) {
      std::error_code ec;
      if (!fs::is_regular_file(node.path_value(key), ec)) continue;  // a kind name, not a file
      const scene::InputNode file = node.load_referenced(key);
      const std::string content = scene::to_yaml(file);
      out.push_back({child, node.path_value(key), sha256_hex(content), content});
      add_referenced(file, child, out);
    } else {
      add_referenced(node[key], child, out);
    }
  }
}

}  // namespace

std::vector<RecordedInput> recorded_inputs(const std::string& scene_path,
                                           const scene::InputNode& scene) {
  const std::string content = scene::to_yaml(scene);
  std::vector<RecordedInput> out = {{"scene", scene_path, sha256_hex(content), content}};
  add_referenced(scene, "", out);
  return out;
}

std::string inputs_fingerprint(const std::string& command,
                               const std::vector<RecordedInput>& inputs) {
  std::string all = command;
  for (const auto& f : inputs) all += "\n" + f.role + " " + f.sha256;
  return sha256_hex(all);
}

void record_inputs(output::ProvenanceInputs& in, const std::string& command,
                   const std::string& scene_path, const scene::InputNode& scene) {
  in.resolved_scene = scene::to_yaml(scene);
  const auto inputs = recorded_inputs(scene_path, scene);
  for (const auto& f : inputs)
    in.inputs.push_back(
        {{"role", f.role}, {"path", f.path}, {"sha256", f.sha256}, {"content", f.content}});
  in.inputs_fingerprint = inputs_fingerprint(command, inputs);
}

void write_run_checkpoint(const Context& ctx, const std::string& file,
                          const RunCheckpoint& checkpoint) {
  on_rank0(ctx, [&] { output::write_checkpoint(file, to_data(checkpoint)); });
}

RunCheckpoint load_run_checkpoint(const Context& ctx, const std::string& dir,
                                  const std::vector<InputFile>& inputs,
                                  const std::vector<std::string>& overrides) {
  const std::string file = dir + "/" + output::kCheckpointName;
  RunCheckpoint c;
  std::string why;
  if (ctx.rank == 0) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      why = "'" + dir + "' is not a folder";
    else if (!fs::exists(file, ec))
      why = "'" + dir + "' holds no checkpoint (" + output::kCheckpointName +
            "): runs write one when interrupted (SIGINT/SIGTERM), when stopped early "
            "(-ts_max_steps) and every output.checkpoint_every steps";
    else if (!fs::exists(dir + "/results.h5", ec))
      why = "'" + dir + "' holds a checkpoint but no results.h5";
    if (why.empty()) {
      try {
        auto data = output::read_checkpoint(file);
        c = from_data(data);
        why = damage(c);
        if (!why.empty()) why = file + " is damaged: " + why;
        if (why.empty()) why = mismatch(ctx, c, inputs, dir, overrides);
      } catch (const std::exception& e) {
        why = std::string("cannot read the checkpoint: ") + e.what();
      }
    }
  }
  why = broadcast_text(ctx.comm, why);
  if (!why.empty()) throw InputError("command line", "--restart", why);
  const std::string scalars = broadcast_text(ctx.comm, ctx.rank == 0 ? scalars_json(c).dump() : "");
  if (ctx.rank != 0) from_scalars_json(nlohmann::json::parse(scalars), c);
  return c;
}

void check_restart_target(const std::string& dir, const std::string& final_dir) {
  const auto restart = fs::weakly_canonical(fs::absolute(dir));
  const auto target = fs::weakly_canonical(fs::absolute(final_dir));
  const auto partial = fs::weakly_canonical(fs::absolute(final_dir + ".partial"));
  if (restart == target || restart == partial)
    throw InputError("command line", "--restart",
                     "'" + dir + "' would become the new result's folder ('" + final_dir +
                         "'); a restart reads it and writes a new result: give that "
                         "one another folder with -o");
}

}  // namespace pcsim::simulation
