// Printing and writing the results of `pcsim static` and `pcsim modes`.
#pragma once

#include <string>

#include "command.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/modes.hpp"
#include "pcsim/catenary/statics.hpp"
#include "pcsim/output/output_dir.hpp"

namespace pcsim::app {

void print_static_summary(const CommandContext& ctx, const assembly::CatenarySystem& system,
                          const catenary::StaticResult& result);

// static.h5 (node values, droppers, tensions, Newton history), the deformed
// mesh (static_mesh.h5 + static.xdmf) and summary.json.
void write_static_results(const CommandContext& ctx, const OutputDir& out,
                          const assembly::CatenarySystem& system,
                          const catenary::StaticResult& result, const std::string& scene_name);

// modes.h5 + modes.xdmf (one grid per mode, animatable) and summary.json.
void write_modes_results(const CommandContext& ctx, const OutputDir& out,
                         const assembly::CatenarySystem& system,
                         const catenary::StaticResult& statics, const catenary::ModesResult& modes,
                         const std::string& scene_name);

}  // namespace pcsim::app
