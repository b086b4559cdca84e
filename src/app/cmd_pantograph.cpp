// `pcsim pantograph SCENE.yaml`: studies of the pantograph alone (thesis chapter 2).
// Scene: pcsim/scene/pantograph_scene.hpp; studies: pcsim/simulation/pantograph_study.hpp;
// output (summary.json, HDF5 histories/curves): pcsim/output/pantograph_results.hpp.
#include <exception>

#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/pantograph_results.hpp"
#include "pcsim/scene/pantograph_scene.hpp"
#include "pcsim/simulation/pantograph_study.hpp"
#include "pcsim/solvers/pantograph_time.hpp"

namespace {

using namespace pcsim;
using pcsim::app::CommandContext;

int run_pantograph(const CommandContext& ctx) {
  app::PantographInputs in = app::read_pantograph_inputs(ctx);
  const scene::InputNode& node = in.scene;
  pantograph::StudyScene& study = in.study;
  const std::string& name = in.name;
  if (study.study_type == "time") solvers::pantograph_ts_type();  // checked before any work
  output::OutputDir out(ctx.comm, ctx.output_request(node));
  app::print0(ctx, "pcsim pantograph: scene '%s', %s model, study %s\n", name.c_str(),
              study.model->kind().c_str(), study.study_type.c_str());
  // The pantograph alone is tiny: rank 0 does the work; the others wait for its outcome.
  app::on_rank0(ctx, [&] {
    const auto result = simulation::run_pantograph_study(study);
    app::print0(ctx, "%s", output::write_pantograph_study(out, name, study, result).c_str());
  });
  out.commit();
  app::print0(ctx, "results in %s\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND_HELP(pantograph_help, "pantograph",
                   "scene sections (docs/scene-format.md, \"Pantograph study scenes\"):\n"
                   "  name         scene name: results go to out/<name>/ (default: the file name)\n"
                   "  pantograph   model: FILE (meshes/pantographs/), effects: {...}\n"
                   "  speed_kmh    train speed for the aerodynamic force [km/h] (0)\n"
                   "  equilibrium  contact_force [N], working_height [m]\n"
                   "  study        type: time|modes|frf|sweep|calibrate and its keys\n"
                   "  base, set    composition: a base scene, keys set by path\n"
                   "results: summary.json; time.h5, frf.h5 or sweep.h5 by study\n");
PCSIM_COMMAND("pantograph", "pantograph alone: time response, modes, FRFs, calibration",
              run_pantograph);
