// The modal bases a sweep's cases need, told before any case runs: the
// cases' catenary designs as the modal cache keys them
// (output/modal_cache.hpp: design, mesh, conditions, form-finding, full
// shapes), each with the cut-offs its cases ask for, and whether the cache
// folder already serves it (by the files' names; nothing read).
#pragma once

#include <cstddef>
#include <map>
#include <set>
#include <string>

#include "command.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace pcsim::app {

class SweepBases {
 public:
  // One case, as read and checked (RunInputs.run); 'dofs' its catenary's unknowns.
  void add(const CommandContext& ctx, const scene::RunScene& run, long dofs);
  // The line rank 0 prints ("" when no case is modal).
  std::string summary() const;

 private:
  struct Design {
    std::set<double> cutoffs;  // Hz (<= 0: every mode)
    std::size_t cases = 0;
    long dofs = 0;
    bool cached = false;  // the cache serves its highest cut-off
  };
  std::map<std::string, Design> designs_;  // by cache key
  std::size_t modal_cases_ = 0;
};

}  // namespace pcsim::app
