// `pcsim study accuracy SCENE.yaml`: what accuracy costs in time. Runs the
// scene over a grid of fidelity (nonlinear, linear, modal catenary), time
// step, element length and modal cut-off, and writes the error of each
// EN 50318 figure against the finest FE run with the cost of every run
// (output/accuracy_study.hpp): accuracy.csv, accuracy.md, accuracy.svg.
// The grid (options, listed by -help):
//   -study_models nonlinear,linear,modal
//   -study_dt_factors 0.5,1,2,5      (multiples of the scene's dt)
//   -study_h_factors 0.5,1,2         (multiples of the design's element length)
//   -study_cutoff_factors 0.6,0.8,1,1.2  (modal cut-off over cutoff_hz/(1-v/c))
//   -study_vertical true             (also the modal run with vertical modes only)
//   -study_grid star|full            (star: one factor at a time around the scene's
//                                     values, plus the finest FE run; full: every combination)
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/output/accuracy_study.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/study_run.hpp"

namespace {

using namespace pcsim;
using catenary::CatenaryFidelity;

struct Grid {
  std::vector<CatenaryFidelity> models = {CatenaryFidelity::nonlinear, CatenaryFidelity::linear,
                                          CatenaryFidelity::modal};
  std::vector<double> dt = {0.5, 1, 2, 5}, h = {0.5, 1, 2}, cutoff = {0.6, 0.8, 1.0, 1.2};
  bool vertical = true, full = false;
};

std::vector<double> read_factors(const char* name, const char* help, std::vector<double> values) {
  PetscInt n = 16;
  PetscReal buffer[16];
  PetscBool set = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetRealArray(nullptr, nullptr, name, buffer, &n, &set));
  if (!set) return values;
  values.assign(buffer, buffer + n);
  for (double v : values)
    if (!(v > 0)) throw InputError("command line", name, std::string(help) + " must be > 0");
  return values;
}

Grid read_grid() {
  Grid g;
  char text[256];
  PetscBool set = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetString(nullptr, nullptr, "-study_models", text, sizeof(text), &set));
  if (set) {
    g.models.clear();
    std::stringstream list(text);
    for (std::string m; std::getline(list, m, ',');) {
      if (m == "nonlinear")
        g.models.push_back(CatenaryFidelity::nonlinear);
      else if (m == "linear")
        g.models.push_back(CatenaryFidelity::linear);
      else if (m == "modal")
        g.models.push_back(CatenaryFidelity::modal);
      else
        throw InputError("command line", "-study_models",
                         "'" + m + "' is not nonlinear, linear or modal");
    }
  }
  g.dt = read_factors("-study_dt_factors", "time-step factors", g.dt);
  g.h = read_factors("-study_h_factors", "element-length factors", g.h);
  g.cutoff = read_factors("-study_cutoff_factors", "cut-off factors", g.cutoff);
  PetscBool vertical = PETSC_TRUE;
  PCSIM_PETSC(PetscOptionsGetBool(nullptr, nullptr, "-study_vertical", &vertical, nullptr));
  g.vertical = vertical;
  PCSIM_PETSC(PetscOptionsGetString(nullptr, nullptr, "-study_grid", text, sizeof(text), &set));
  if (set && std::string(text) != "star" && std::string(text) != "full")
    throw InputError("command line", "-study_grid", "must be star or full");
  g.full = set && std::string(text) == "full";
  return g;
}

// Star: the scene's values (factor 1) with one factor changed at a time, and
// the finest FE run (smallest dt and h); full: every combination. Modal runs
// with the highest cut-off first (later ones reuse its modes). scene_cutoff:
// the scene's modal cut-off as a factor (a cut-off factor equal to it is the
// base run, not run twice).
std::vector<simulation::StudyVariant> variants(const Grid& g, bool parametric,
                                               double scene_cutoff) {
  std::vector<simulation::StudyVariant> list;
  const std::vector<double> hs = parametric ? g.h : std::vector<double>{1.0};
  for (CatenaryFidelity m : g.models) {
    const bool modal = m == CatenaryFidelity::modal;
    const std::vector<double> cutoffs = modal ? g.cutoff : std::vector<double>{0.0};
    if (g.full) {
      for (double dt : g.dt)
        for (double h : hs)
          for (double fc : cutoffs) list.push_back({m, dt, h, fc, false});
    } else {
      list.push_back({m, 1, 1, 0, false});
      if (m == CatenaryFidelity::nonlinear) continue;  // the costliest: its base run only
      for (double dt : g.dt)
        if (dt != 1) list.push_back({m, dt, 1, 0, false});
      for (double h : hs)
        if (h != 1) list.push_back({m, 1, h, 0, false});
      if (modal)
        for (double fc : cutoffs)
          if (std::abs(fc - scene_cutoff) > 1e-9) list.push_back({m, 1, 1, fc, false});
    }
    if (modal && g.vertical) list.push_back({m, 1, 1, 0, true});
  }
  // The finest FE run (the reference): linear if the grid has it.
  const double dt_min = *std::min_element(g.dt.begin(), g.dt.end());
  const double h_min = *std::min_element(hs.begin(), hs.end());
  const auto fe = std::find_if(g.models.begin(), g.models.end(),
                               [](CatenaryFidelity m) { return m != CatenaryFidelity::modal; });
  const bool linear =
      std::find(g.models.begin(), g.models.end(), CatenaryFidelity::linear) != g.models.end();
  if (!g.full && fe != g.models.end()) {
    const simulation::StudyVariant finest{linear ? CatenaryFidelity::linear : *fe, dt_min, h_min, 0,
                                          false};
    const bool listed =
        std::any_of(list.begin(), list.end(), [&](const simulation::StudyVariant& v) {
          return v.model == finest.model && v.dt_factor == dt_min && v.h_factor == h_min;
        });
    if (!listed) list.push_back(finest);
  }
  // Modal runs per mesh by decreasing cut-off (later ones reuse the first one's modes).
  const auto effective = [](const simulation::StudyVariant& v) {
    return v.cutoff_factor > 0 ? v.cutoff_factor : catenary::kModalCutoffMargin;
  };
  std::vector<simulation::StudyVariant> modal, others;
  for (const auto& v : list) (v.model == CatenaryFidelity::modal ? modal : others).push_back(v);
  std::stable_sort(modal.begin(), modal.end(), [&](const auto& a, const auto& b) {
    return a.h_factor != b.h_factor ? a.h_factor < b.h_factor : effective(a) > effective(b);
  });
  others.insert(others.end(), modal.begin(), modal.end());
  return others;
}

std::string cutoff_note(const simulation::StudyVariant& v) {
  if (v.model != CatenaryFidelity::modal || v.cutoff_factor <= 0) return "";
  char text[64];
  std::snprintf(text, sizeof(text), ", cut-off x %g", v.cutoff_factor);
  return text;
}

// The 1-minute load average (/proc/loadavg; -1 if unreadable): the machine's
// load while the costs were measured, recorded with the table.
double load_average() {
  double load = -1;
  std::ifstream("/proc/loadavg") >> load;
  return load;
}

int study(const app::CommandContext& ctx) {
  if (ctx.subcommand != "accuracy")
    throw InputError("command line", "study",
                     "unknown study '" + ctx.subcommand + "' (pcsim study accuracy SCENE.yaml)");
  const scene::InputNode scene = ctx.load_scene();
  const auto base = scene::load_run_scene(scene);  // checks the scene once
  if (base.window)
    throw InputError(scene.file(), "window",
                     "pcsim study accuracy runs the whole line; the moving window's error is "
                     "measured by runs/bench_window.sh (docs/scaling.md)");
  const Grid grid = read_grid();
  const bool parametric = simulation::design_element_length(scene) > 0;
  const auto& wire = base.catenary.mesh.wires[base.catenary.mesh.contact_wire];
  const double scene_cutoff =
      base.catenary.modal.max_frequency_hz /
      catenary::doppler_frequency(base.cutoff_hz, base.speed, catenary::wave_speed(wire));
  const auto list = variants(grid, parametric, scene_cutoff);
  if (!parametric)
    app::print0(ctx,
                "  note: the design is explicit (no element_length): -study_h_factors ignored\n");
  const std::string name = ctx.scene_name(scene);
  output::OutputRequest request = ctx.output_request(scene);
  if (ctx.output_dir.empty()) request.dir = "out/" + name + "-accuracy";
  output::OutputDir out(ctx.comm, request);
  app::print0(ctx, "pcsim study accuracy: scene '%s', %zu runs on %d rank(s)\n", name.c_str(),
              list.size(), ctx.size);
  output::StudyTable table;
  table.scene = name;
  table.ranks = ctx.size;
  table.load_before = load_average();
  std::filesystem::create_directories(out.file("runs"));
  const simulation::SceneSource source{ctx.scene_path, ctx.overrides, scene, ctx.provenance(scene)};
  for (std::size_t i = 0; i < list.size(); ++i) {
    output::StudyRun probe;
    probe.model = catenary::fidelity_name(list[i].model);
    app::print0(ctx, "  [%zu/%zu] %s, dt x %g, h x %g%s%s ...", i + 1, list.size(),
                probe.model.c_str(), list[i].dt_factor, list[i].h_factor,
                cutoff_note(list[i]).c_str(), list[i].vertical_only ? ", vertical modes" : "");
    const std::string dir = out.file("runs/" + std::to_string(i + 1));
    auto run = simulation::run_variant(ctx, source, list[i], dir);
    if (run.ok)
      app::print0(ctx, " %.3f ms/step, RTF %.2f\n", run.ms_per_step, run.real_time_factor);
    else
      app::print0(ctx, " failed: %s\n", run.failure.c_str());
    table.runs.push_back(std::move(run));
  }
  table.load_after = load_average();
  output::evaluate_study(table);
  const std::string markdown = output::accuracy_markdown(table);
  app::on_rank0(ctx, [&] {
    output::write_accuracy_csv(out.file("accuracy.csv"), table);
    std::ofstream(out.file("accuracy.md")) << "# What accuracy costs: " << name << "\n\n"
                                           << markdown;
    output::write_accuracy_svg(out.file("accuracy.svg"), table);
    std::ofstream(out.file("study.json")) << output::study_json(table).dump(2) << "\n";
  });
  app::print0(ctx, "\n%s\n", markdown.c_str());
  out.commit();
  app::print0(ctx, "  results in %s/ (accuracy.csv, accuracy.md, accuracy.svg, runs/)\n",
              out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND_HELP(
    study_help, "study",
    "subcommand: accuracy (pcsim study accuracy SCENE.yaml): a run scene (the sections of\n"
    "'pcsim run --help') over a grid; the grid (PETSc options, docs/fidelity.md):\n"
    "  -study_models nonlinear,linear,modal   fidelity levels\n"
    "  -study_dt_factors 0.5,1,2,5            multiples of the scene's dt\n"
    "  -study_h_factors 0.5,1,2               multiples of the design's element_length\n"
    "  -study_cutoff_factors 0.6,0.8,1,1.2    modal cut-off over cutoff_hz / (1 - v/c)\n"
    "  -study_vertical true                   also the modal run with vertical modes only\n"
    "  -study_grid star|full                  one factor at a time, or every combination\n"
    "results: accuracy.csv, accuracy.md, accuracy.svg, study.json, runs/<n>/\n", );

PCSIM_COMMAND_WITH_SUBCOMMAND("study",
                              "studies of a run scene: 'study accuracy SCENE' (accuracy against "
                              "cost over fidelity, dt, mesh and modal cut-off)",
                              study);
