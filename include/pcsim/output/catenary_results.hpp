// Results of `pcsim static` and `pcsim modes` on disk: static.h5 (node
// values, droppers, tensions, Newton history), the deformed mesh
// (static_mesh.h5 + static.xdmf for ParaView), modes.h5 + modes.xdmf (one
// grid per mode, animatable, its frequency and direction as field data) and
// summary.json. Called on rank 0.
#pragma once

#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/results.hpp"
#include "pcsim/output/output_dir.hpp"

namespace pcsim::output {

struct CatenaryRunInfo {
  std::string scene_name;
  long dofs = 0;
  int ranks = 1;
  bool form_finding = false;
};

void write_static_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                          const catenary::StaticResult& result, const CatenaryRunInfo& info);

// elasticity.csv: station, uplift per force [mm per 100 N], uplift [m],
// the contact wire loaded.
void write_elasticity(const OutputDir& out, const catenary::ElasticityResult& result);

// Per mode shape (x, y, z per node): 1 if the contact wires' motion is mostly
// vertical (the sum of z^2 over their nodes at least that of y^2), 0 if
// mostly lateral. A mesh without contact wire: all nodes count.
std::vector<long> modes_vertical(const catenary::CatenaryMesh& mesh,
                                 const std::vector<std::vector<double>>& shapes);

void write_modes_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                         const catenary::StaticResult& statics, const catenary::ModesResult& modes,
                         const CatenaryRunInfo& info);

}  // namespace pcsim::output
