// run_cases OUT SCENE...: runs every scene through the run pipeline
// (simulation/run.hpp) one after the other in this one process, each into
// OUT/<n> (n = 1, 2, ...), as `pcsim run SCENE -o OUT/<n>` would in a process
// of its own. tests/simulation/test_two_runs.sh compares the two.
#include <slepcsys.h>

#include <cstdio>
#include <exception>
#include <string>

#include "pcsim/core/blas_kernels.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"

namespace {

void run_case(const std::string& path, const std::string& dir) {
  using namespace pcsim;
  const auto ctx = simulation::Context::of(PETSC_COMM_WORLD);
  const scene::InputNode composed = scene::load_composed(path, {});
  auto scene = scene::load_run_scene(composed);
  simulation::RunRequest request;
  request.name = composed.has("name") ? composed.get_string("name") : "case";
  request.scene_path = path;
  request.inputs = simulation::run_input_files(path, composed);
  output::OutputRequest output{dir,          "command line",          "-o", "run", path,
                       request.name, nlohmann::json::object()};
  output::OutputDir out(ctx.comm, output);
  const auto outcome = simulation::run(ctx, scene, request, out);
  if (!outcome.complete) throw std::runtime_error("interrupted");
  out.commit();
}

}  // namespace

int main(int argc, char** argv) {
  pcsim::select_blas_kernels();  // as pcsim's main: the same BLAS kernels, the same bits
  if (SlepcInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  int status = 0;
  try {
    if (argc < 3) throw std::runtime_error("usage: run_cases OUT SCENE...");
    for (int i = 2; i < argc; ++i)
      run_case(argv[i], std::string(argv[1]) + "/" + std::to_string(i - 1));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_cases: %s\n", e.what());
    status = 1;
  }
  SlepcFinalize();
  return status;
}
