// The catenary model of a run scene at its fidelity (catenary.model):
// FECatenary (nonlinear or linearised cables) or ModalCatenary, whose reduced
// basis comes from the cache folder (output/modal_cache.hpp) or is computed
// (solvers/modal_basis.hpp) and stored there. Shared by `pcsim run` and
// `pcsim study accuracy`.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "pcsim/assembly/catenary_model.hpp"
#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

struct CatenarySetup {
  std::unique_ptr<assembly::CatenaryModel> model;
  bool modal = false;
  bool cache_hit = false;
  bool basis_kept = false;  // the basis kept in memory by an earlier run of this process
  std::string cache_file;
  std::string basis_file;        // the assembled basis read or stored (output::basis_cache_file)
  bool basis_assembled = false;  // assembled by this run (not read as assembled)
  double basis_seconds = 0;      // computing the basis (0 when read from the cache)
  double setup_seconds = 0;      // reading or computing it
  int basis_size = 0, eigenmodes = 0, dropped_modes = 0;
  int column_blocks = 1;  // the basis's (catenary/reduced_basis.hpp)
  double cutoff_hz = 0;
  // For summary.json and the console.
  nlohmann::json facts() const;
};

// While one lives, the modal data this process computes keep what they were
// computed with (simulation::ModalDataBuilder: operators, factor, dropper
// shapes, a window's vectors), and data of the same catenary at a higher
// cut-off compute only the modes above the last one: the accuracy pilot's
// raised cut-offs (accuracy_pilot.cpp). When the last one ends, they are
// freed (collective: every rank of the runs ends it).
class ModalExtensionScope {
 public:
  ModalExtensionScope();
  ~ModalExtensionScope();
  ModalExtensionScope(const ModalExtensionScope&) = delete;
  ModalExtensionScope& operator=(const ModalExtensionScope&) = delete;
  // The next computation is the last one this scope extends: it frees what
  // it was computed with as soon as it can (a window's vectors before its
  // products are summed), as a computation outside a scope does.
  void last_computation_next();
};

// The last modal data this process computed: the modes computed, those kept
// from a lower cut-off (ModalExtensionScope) and that cut-off; 'serial'
// counts the computations (0: none yet).
struct ModalComputation {
  long serial = 0, computed = 0, kept = 0;
  double kept_below_hz = 0;
  // > 0: the modes below it computed again, their rows not in the cache
  // file this process wrote them to (not written, or replaced since).
  double again_below_hz = 0;
};
ModalComputation last_modal_computation();

// extra_dofs: the pantographs' unknowns. Snapshots need a modal model's full
// shapes (run.snapshot_every > 0).
CatenarySetup make_catenary_model(const Context& ctx, const scene::RunScene& run,
                                  const simulation::StaticConfiguration& statics,
                                  PetscInt extra_dofs);

// The coupled system of the scene on the static configuration (moves the
// scene's pantograph models in), its catenary from make_catenary_model
// (setup keeps the facts; its model is moved into the system).
std::unique_ptr<assembly::CoupledSystem> make_coupled_system(
    const Context& ctx, scene::RunScene& run, const simulation::StaticConfiguration& statics,
    CatenarySetup& setup);

}  // namespace pcsim::simulation
